// The Python module eqhb._eqhb (wrapped by the package eqhb): models from
// scene files or arrays, backends by name, solve, sweep, simulate. Bad input
// raises eqhb.InputError (a ValueError) whose message names the field.
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <complex>
#include <optional>

#include "conversions.h"
#include "py_model.h"
#include "sweep_watch.h"
#include "eqhb/app/modes.h"
#include "eqhb/app/shoot.h"
#include "eqhb/app/simulate.h"
#include "eqhb/app/solve.h"
#include "eqhb/app/study.h"
#include "eqhb/app/sweep.h"
#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/coarse_start.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/output/study_json.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/orbits/piecewise_linear_flow.h"
#include "eqhb/output/backbone_writers.h"
#include "eqhb/output/synthesis_writers.h"
#include "eqhb/app/synthesis.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/solvers/deadline.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/stability/hill_stability.h"
#include "eqhb/structures/structure_matrices.h"
#include "eqhb/version.h"

namespace py = pybind11;
using namespace eqhb;
using namespace eqhb::python;

namespace {

// The library's work with the GIL released (it calls no Python), so that
// other Python threads run meanwhile.
template <class Work>
auto withoutGil(const Work& work) {
  py::gil_scoped_release unlocked;
  return work();
}

// The solver options of a call's arguments (the package's _hb_args).
SolverOptions solverOptions(const py::dict& a) {
  SolverOptions options;
  options.residual_tolerance = a["tolerance"].cast<double>();
  options.max_iterations = a["max_iterations"].cast<int>();
  options.max_evaluations = a["max_evaluations"].cast<int>();
  options.time_limit = a["time_limit"].cast<double>();
  options.backend = a["options"].cast<std::map<std::string, std::string>>();
  const std::string linear_algebra = a["linear_algebra"].cast<std::string>();
  if (linear_algebra == "dense") options.linear_algebra = LinearAlgebra::kDense;
  else if (linear_algebra == "sparse") options.linear_algebra = LinearAlgebra::kSparse;
  else if (linear_algebra != "auto")
    throwInputError("linear_algebra", "\"" + linear_algebra + "\"", "must be \"auto\", \"dense\" or \"sparse\"");
  std::string why;
  if (!options.isValid(&why)) throw InputError(why);
  return options;
}

bool condensedSystem(const std::string& system) {
  if (system != "condensed" && system != "full")
    throwInputError("system", "\"" + system + "\"", "must be \"condensed\" or \"full\"");
  return system == "condensed";
}

// The scene settings of one call: ω, H, N, form, ρ and formulation over the
// model's document.
struct SceneArgs {
  std::optional<double> omega;
  std::optional<int> harmonics, samples;
  std::optional<std::string> form;
  std::optional<double> rho;
  std::optional<std::string> formulation;
  std::optional<std::vector<std::string>> show;  // the outputs' DOFs (scenes/dof_choice.h)
  std::optional<std::string> peak_dof;
  app::SceneSettings of(const PyModel& m) const {
    app::SceneSettings s = sceneSettings(m, omega, harmonics, samples, form, rho, formulation);
    s.show = show;
    s.peak_dof = peak_dof;
    return s;
  }
};

// The backend, system, limits and fallbacks every call that solves takes.
void readSolverChoice(const py::dict& a, app::SolverChoice* o) {
  o->solver = a["solver"].cast<std::string>();
  o->condensed = condensedSystem(a["system"].cast<std::string>());
  o->solver_options = solverOptions(a);
  o->fallback = a["fallback"].cast<std::string>();
}

// Stability, error estimate and accuracy target (solve and sweep).
void readSolutionChecks(const py::dict& a, app::SolutionChecks* o) {
  o->stability = a["stability"].cast<bool>();
  o->stability_method = a["stability_method"].cast<std::string>();
  o->stability_time_limit = a["stability_time_limit"].cast<double>();
  o->error_estimate = a["error_estimate"].cast<bool>();
  o->accuracy = a["accuracy"].cast<std::optional<double>>();
  o->max_harmonics = a["max_harmonics"].cast<int>();
  o->accuracy_test = a["accuracy_test"].cast<std::string>();
}

// The harmonic-balance options every call that solves takes.
app::SolveOptions hbOptions(const py::dict& a) {
  app::SolveOptions o;
  readSolverChoice(a, &o);
  o.cold_start = a["cold_start"].cast<std::string>();
  return o;
}

SceneArgs sceneArgs(const py::dict& a) {
  SceneArgs s;
  s.omega = a["omega"].cast<std::optional<double>>();
  s.harmonics = a["harmonics"].cast<std::optional<int>>();
  s.samples = a["samples"].cast<std::optional<int>>();
  s.form = a["form"].cast<std::optional<std::string>>();
  s.rho = a["rho"].cast<std::optional<double>>();
  s.formulation = a["formulation"].cast<std::optional<std::string>>();
  if (a.contains("show")) s.show = a["show"].cast<std::optional<std::vector<std::string>>>();
  if (a.contains("peak_dof")) s.peak_dof = a["peak_dof"].cast<std::optional<std::string>>();
  return s;
}

// eqhb.solve: app::solve with the call's settings and options (`args`, checked
// and named by the package's solve).
py::dict solve(const PyModel& m, const py::dict& args) {
  const app::SceneSettings scene = sceneArgs(args).of(m);
  app::SolveOptions o = hbOptions(args);
  if (!args["initial"].is_none()) o.initial = args["initial"].cast<Eigen::VectorXd>();
  o.from_harmonics = args["from_harmonics"].cast<std::optional<int>>();
  o.repeat = args["repeat"].cast<int>();
  readSolutionChecks(args, &o);
  o.refine = args["refine"].is_none() ? std::string() : args["refine"].cast<std::string>();
  o.restitution = args["restitution"].cast<double>();
  o.refine_harmonics = args["refine_harmonics"].is_none() ? 0 : args["refine_harmonics"].cast<int>();
  return solveDict(withoutGil([&] { return app::solve(scene, o); }));
}

// Floquet multipliers of a harmonic-balance solution by Hill's method.
py::dict stability(const PyModel& m, const Eigen::VectorXd& full, std::optional<double> omega,
                   std::optional<int> harmonics, std::optional<int> samples) {
  const HbModel model = withSettings(m.scene.model, omega, harmonics, samples);
  const Eigen::Index full_size =
      static_cast<Eigen::Index>(model.basis.size()) * (model.structure.dofs() + model.lawComponents());
  if (full.size() != full_size || !full.allFinite())
    throwInputError("solution", "(" + std::to_string(full.size()) + " values)",
                    "must be a finite full coefficient vector [x; lambda] of " + std::to_string(full_size) +
                        " values (the \"full\" entry of a solution at these settings)");
  return stabilityDict(withoutGil([&] { return hillStability(model, full); }));
}

// Python names the range start and stop; the library names it from and to.
std::string withPythonNames(const std::string& message) {
  std::string out = message;
  for (const auto& [field, name] :
       {std::pair<std::string, std::string>{"from", "start"}, {"to", "stop"}, {"scene", "model"}})
    if (out.rfind(field + " = ", 0) == 0) {
      out = name + out.substr(field.size());
      break;
    }
  const std::string phrase = "give from and to", replaced = "give start and stop";
  for (size_t at = out.find(phrase); at != std::string::npos; at = out.find(phrase, at + 1))
    out.replace(at, phrase.size(), replaced);
  return out;
}

// The work's result; its input errors reworded with Python's names.
template <class Work>
auto inPythonTerms(const Work& work) {
  try {
    return work();
  } catch (const InputError& e) {
    throw InputError(withPythonNames(e.what()));
  }
}

// eqhb.sweep: app::sweep with the call's settings and options, as `eqhb sweep`.
py::dict sweep(const PyModel& m, const py::dict& args) {
  const app::SceneSettings scene = sceneArgs(args).of(m);
  const std::string method = args["method"].cast<std::string>();
  if (method != "sequential" && method != "arclength")
    throwInputError("method", "\"" + method + "\"", "must be \"sequential\" or \"arclength\"");
  app::SweepOptions o;
  readSolverChoice(args, &o);
  readSolutionChecks(args, &o);
  o.from = args["start"].cast<std::optional<double>>();
  o.to = args["stop"].cast<std::optional<double>>();
  o.arclength = method == "arclength";
  o.step = args["step"].cast<std::optional<double>>();
  o.min_step = args["min_step"].cast<std::optional<double>>();
  o.max_step = args["max_step"].cast<std::optional<double>>();
  o.max_points = args["max_points"].cast<int>();
  o.curve_time_limit = args["curve_time_limit"].cast<double>();
  SweepWatch watch(args["progress"]);
  o.stop_requested = watch.stopRequested();
  const app::SweepPlan plan = inPythonTerms([&] { return app::planSweep(scene, o); });
  app::SweepCallbacks callbacks;
  callbacks.point = watch.callback();
  const app::SweepResult result = withoutGil([&] { return app::sweep(plan, callbacks); });
  watch.raiseIfFailed();
  return sweepDict(result);
}

// eqhb.study: app::study with the call's settings and options, as `eqhb
// study` on threads; the rows as study.json holds them, and the run's counts.
py::dict study(const PyModel& m, const py::dict& args) {
  const app::SceneSettings scene = sceneArgs(args).of(m);
  app::StudyOptions o;
  readSolverChoice(args, &o);
  o.vary = args["vary"].cast<std::vector<std::string>>();
  o.lhs = args["lhs"].cast<std::optional<int>>();
  o.seed = args["seed"].cast<unsigned long long>();
  o.mode = args["mode"].cast<std::string>();
  o.from = args["start"].cast<std::optional<double>>();
  o.to = args["stop"].cast<std::optional<double>>();
  o.step = args["step"].cast<double>();
  o.dof = args["dof"].cast<std::string>();
  o.coarse_points = args["coarse_points"].cast<int>();
  o.max_peaks = args["max_peaks"].cast<int>();
  o.threads = args["threads"].cast<int>();
  o.out = args["out"].cast<std::string>();
  const app::StudySetup setup = inPythonTerms([&] { return app::setupStudy(scene, o); });
  const app::StudyRun run = withoutGil([&] { return app::runStudy(setup, o.threads); });
  output::writeStudyJson(o.out + "/study.json", run);
  py::dict d = fromJson(output::studyJson(run));
  d["total"] = run.total;
  d["computed"] = run.computed;
  d["failed"] = run.failed();
  d["succeeded"] = run.succeeded();
  d["seconds"] = run.seconds;
  d["threads"] = run.how;
  return d;
}

app::TimeSettings timeSettings(const py::dict& a) {
  app::TimeSettings t;
  t.step = a["step"].cast<std::optional<double>>();
  t.periods = a["periods"].cast<std::optional<int>>();
  t.theta = a["theta"].cast<std::optional<double>>();
  t.periodic_tolerance = a["periodic_tolerance"].cast<std::optional<double>>();
  t.max_seconds = a["max_seconds"].cast<double>();
  t.restitution = a["restitution"].cast<double>();
  return t;
}

// eqhb.simulate: the reference with the scene's [time_reference] defaults,
// from rest, from `initial` or (from_hb) from the harmonic-balance solution.
py::dict simulate(const PyModel& m, const py::dict& args) {
  const app::SceneSettings scene = sceneArgs(args).of(m);
  app::SimulateOptions o;
  o.time = timeSettings(args);
  o.from_hb = args["from_hb"].cast<bool>();
  if (o.from_hb) o.hb = hbOptions(args);
  if (!args["initial"].is_none()) {
    if (o.from_hb) throwInputError("initial", "(vector)", "give initial or from_hb, not both");
    o.initial = args["initial"].cast<Eigen::VectorXd>();
  }
  return simulationDict(withoutGil([&] { return app::simulate(scene, o); }));
}

// eqhb.compare: a harmonic-balance solve against the reference started from it.
py::dict compare(const PyModel& m, const py::dict& args) {
  const app::SceneSettings scene = sceneArgs(args).of(m);
  app::CompareOptions o;
  o.time = timeSettings(args);
  o.from_rest = args["from_rest"].cast<bool>();
  o.hb = hbOptions(args);
  return comparisonDict(withoutGil([&] { return app::compare(scene, o); }));
}

// eqhb.shoot: the exact periodic orbit from the harmonic-balance solve of
// the scene, as `eqhb shoot` (app::shoot), with one period sampled.
py::dict shoot(const PyModel& m, const py::dict& args) {
  const app::SceneSettings scene = sceneArgs(args).of(m);
  app::ShootOptions o;
  o.hb = hbOptions(args);
  o.from_hb = args["from_hb"].cast<std::optional<int>>();
  o.restitution = args["restitution"].cast<double>();
  o.tolerance = args["shooting_tolerance"].cast<double>();
  o.max_iterations = args["shooting_max_iterations"].cast<int>();
  o.trajectory = true;
  return orbitDict(withoutGil([&] { return app::shoot(scene, o); }));
}

// eqhb.modes: the nonlinear mode's backbone, as `eqhb modes` (app::modes);
// the dict holds every key of `eqhb modes --json`.
py::dict modes(const PyModel& m, const py::dict& args) {
  const app::SceneSettings scene = sceneArgs(args).of(m);
  app::ModesOptions o;
  o.mode = args["mode"].cast<int>();
  o.branch = args["branch"].cast<std::string>();
  o.from = args["from"].cast<std::optional<double>>();
  o.to = args["to"].cast<std::optional<double>>();
  o.points = args["points"].cast<int>();
  o.backbone_time_limit = args["backbone_time_limit"].cast<double>();
  o.solver = args["solver"].cast<std::string>();
  o.condensed = condensedSystem(args["system"].cast<std::string>());
  o.solver_options = solverOptions(args);
  const bool synthesis = args["synthesis"].cast<bool>();
  o.synthesis = synthesis;
  nlohmann::json out = withoutGil([&] {
    const app::ModesRun run = app::modes(scene, o);
    nlohmann::json j = output::backboneJson(run);
    if (synthesis) j["synthesis"] = output::synthesisJson(app::compareWithForcedSweep(scene, run, o, app::SweepOptions()));
    return j;
  });
  return fromJson(out).cast<py::dict>();
}

py::list lawList(const HbModel& model) {
  py::list laws;
  for (const auto& l : model.laws) {
    py::list dofs;  // every DOF the law reads (one per component when grounded)
    for (int d : l.attachment.dofs()) dofs.append(d + 1);
    laws.append(py::dict(py::arg("type") = l.law->type(), py::arg("dofs") = dofs));
  }
  return laws;
}

}  // namespace

PYBIND11_MODULE(_eqhb, m) {
  m.doc() = "eqhb: periodic vibrations with dry friction and contact by equality-based harmonic balance";
  m.attr("__version__") = EQHB_VERSION;
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    }
  });

  m.def("solvers", [] {
    py::list out;
    for (const auto& e : registeredSolvers())
      out.append(py::dict(py::arg("name") = e.name, py::arg("description") = e.description));
    return out;
  }, "The backends built in, as dicts {name, description}.");

  py::class_<PyModel>(m, "Model", "A structure with its laws, loads and harmonic-balance settings.")
      .def_static("from_scene",
                  [](const std::string& path, const std::vector<std::string>& overrides) {
                    return modelFromScene(path, overrides);
                  },
                  py::arg("path"), py::arg("overrides") = std::vector<std::string>{},
                  "Loads a scene file; overrides are \"path=value\" strings as for `eqhb --set`.")
      .def_static("_from_text",
                  &modelFromText,
                  py::arg("text"), py::arg("source"))
      .def_static("_from_arrays", &modelFromArrays, py::arg("text"), py::arg("mass"), py::arg("stiffness"),
                  py::arg("damping"))
      .def_property_readonly("name", [](const PyModel& p) { return p.scene.name; })
      .def_property_readonly("dofs", [](const PyModel& p) { return p.scene.model.structure.dofs(); })
      .def_property_readonly("omega", [](const PyModel& p) { return p.scene.model.omega; })
      .def_property_readonly("harmonic_count", [](const PyModel& p) { return p.scene.model.basis.count(); })
      .def_property_readonly("harmonics", [](const PyModel& p) { return p.scene.model.basis.harmonics(); })
      .def_property_readonly("harmonic_set",
                             [](const PyModel& p) { return HarmonicSet::kindName(p.scene.model.basis.kind()); })
      .def_property_readonly("samples", [](const PyModel& p) { return p.scene.model.samples; })
      .def_property_readonly("sweep_range",
                             [](const PyModel& p) -> py::object {
                               if (!p.scene.sweep_from) return py::none();
                               return py::make_tuple(*p.scene.sweep_from, *p.scene.sweep_to);
                             })
      .def_property_readonly("mass", [](const PyModel& p) { return Eigen::MatrixXd(p.scene.model.structure.mass); })
      .def_property_readonly("damping", [](const PyModel& p) { return Eigen::MatrixXd(p.scene.model.structure.damping); })
      .def_property_readonly("stiffness", [](const PyModel& p) { return Eigen::MatrixXd(p.scene.model.structure.stiffness); })
      .def_property_readonly("laws", [](const PyModel& p) { return lawList(p.scene.model); })
      .def("__repr__", [](const PyModel& p) {
        const HbModel& model = p.scene.model;
        return "<eqhb.Model '" + p.scene.name + "': " + std::to_string(model.structure.dofs()) + " DOFs, " +
               std::to_string(model.laws.size()) + " laws, H = " + std::to_string(model.basis.count()) + " (" +
               HarmonicSet::kindName(model.basis.kind()) + "), N = " + std::to_string(model.samples) +
               ", omega = " + formatNumber(model.omega) + ">";
      });

  m.def("_solve", &solve, py::arg("model"), py::arg("args"));
  m.def("_sweep", &sweep, py::arg("model"), py::arg("args"));
  m.def("_study", &study, py::arg("model"), py::arg("args"));
  m.def("_stability", &stability, py::arg("model"), py::arg("full"), py::arg("omega"), py::arg("harmonics"),
        py::arg("samples"));
  m.def("_shoot", &shoot, py::arg("model"), py::arg("args"));
  m.def("_modes", &modes, py::arg("model"), py::arg("args"));
  m.def("_simulate", &simulate, py::arg("model"), py::arg("args"));
  m.def("_compare", &compare, py::arg("model"), py::arg("args"));
}
