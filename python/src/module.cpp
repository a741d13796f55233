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
#include "matrix_argument.h"
#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/coarse_start.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/orbits/piecewise_linear_flow.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/solvers/deadline.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/stability/hill_stability.h"
#include "eqhb/structures/structure_matrices.h"
#include "eqhb/version.h"

namespace py = pybind11;
using namespace eqhb;
using python::curveDict;
using python::matrixArgument;
using python::referenceDict;
using python::resultDict;
using python::solutionDict;

namespace {

// A scene as Python sees it: the model and the scene's own metadata.
struct PyModel {
  Scene scene;
};

// The model of `text` (a scene document whose structure only fixes the DOF
// count) with M, C, K from arrays; the loads and laws come from the text.
PyModel modelFromArrays(const std::string& text, const py::object& mass, const py::object& damping,
                        const py::object& stiffness) {
  StructureMatrices matrices;
  matrices.mass = matrixArgument(mass, "mass");
  matrices.stiffness = matrixArgument(stiffness, "stiffness");
  if (damping.is_none()) {
    matrices.damping.resize(matrices.mass.rows(), matrices.mass.cols());
  } else {
    matrices.damping = matrixArgument(damping, "damping");
  }
  checkStructureMatrices(matrices, 1e-12, MatrixNames{});
  PyModel m{parseScene(text, "model")};
  LinearStructure structure = toLinearStructure(matrices);
  structure.loads = m.scene.model.structure.loads;
  m.scene.model.structure = std::move(structure);
  m.scene.model.validate();
  return m;
}

SolverOptions solverOptions(double tolerance, int max_iterations, int max_evaluations, double time_limit,
                            const std::map<std::string, std::string>& backend) {
  SolverOptions options;
  options.residual_tolerance = tolerance;
  options.max_iterations = max_iterations;
  options.max_evaluations = max_evaluations;
  options.time_limit = time_limit;
  options.backend = backend;
  std::string why;
  if (!options.isValid(&why)) throw InputError(why);
  return options;
}

bool condensedSystem(const std::string& system) {
  if (system != "condensed" && system != "full")
    throwInputError("system", "\"" + system + "\"", "must be \"condensed\" or \"full\"");
  return system == "condensed";
}

// The model with another ω, H or N, validated.
HbModel withSettings(const HbModel& base, std::optional<double> omega, std::optional<int> harmonics,
                     std::optional<int> samples) {
  HbModel model = base;
  if (omega) model.omega = *omega;
  if (harmonics && !samples) model.samples = samplesForHarmonics(model, *harmonics);
  if (harmonics) model.basis = HarmonicSet(model.basis.kind(), *harmonics);
  if (samples) model.samples = *samples;
  if (omega && !(std::isfinite(*omega) && *omega > 0)) throwInputError("omega", formatNumber(*omega), "must be > 0");
  model.validate();
  return model;
}

py::dict solve(const PyModel& m, std::optional<double> omega, std::optional<int> harmonics,
               std::optional<int> samples, const std::string& solver_name, const std::string& system,
               double tolerance, int max_iterations, int max_evaluations, double time_limit,
               const std::map<std::string, std::string>& backend, const std::optional<Eigen::VectorXd>& initial,
               const std::string& cold_start, const std::string& fallback) {
  const HbModel model = withSettings(m.scene.model, omega, harmonics, samples);
  const SolverOptions options = solverOptions(tolerance, max_iterations, max_evaluations, time_limit, backend);
  auto solver = makeSolver(solver_name);
  const OwnedFallbackChain fallbacks(fallback, solver_name, "fallback");
  auto hb = makeHbSystem(model, condensedSystem(system));
  Eigen::VectorXd z0 = Eigen::VectorXd::Zero(hb->size());
  if (initial) {
    const Eigen::Index full_size = static_cast<Eigen::Index>(model.basis.size()) *
                                   (model.structure.dofs() + model.lawComponents());
    if (initial->size() != full_size)
      throwInputError("initial", "(" + std::to_string(initial->size()) + " values)",
                      "must be a full coefficient vector [x; lambda] of " + std::to_string(full_size) +
                          " values (the \"full\" entry of a solution)");
    if (!initial->allFinite()) throwInputError("initial", "(vector)", "must be finite");
    z0 = hb->fromFullCoefficients(*initial);
  }
  if (cold_start != "coarse" && cold_start != "zero")
    throwInputError("cold_start", "\"" + cold_start + "\"", "must be \"coarse\" or \"zero\"");
  // Without an initial guess, start from a coarse harmonic balance (as `eqhb solve`).
  std::optional<CoarseStart> coarse;
  if (!initial && cold_start == "coarse") {
    coarse.emplace(model, condensedSystem(system), LinearAlgebra::kAuto);
  }
  SolverResult result;
  ColdStartReport report;
  {
    py::gil_scoped_release unlocked;
    result = coarse ? coarse->solve(*solver, *hb, options, &report) : solver->solve(*hb, z0, options);
  }
  FallbackReport tried;
  if (!result.converged() && result.termination != Termination::kInvalidOptions) {
    py::gil_scoped_release unlocked;
    result = solveWithFallbacks(*hb, *solver, options, result, !initial, fallbacks.chain(), &tried);
  }
  if (result.termination == Termination::kInvalidOptions) throw InputError("options: " + result.native_message);
  py::dict d = resultDict(result);
  if (report.used) d["seconds"] = report.seconds;  // the coarse solve included
  py::dict cold;
  cold["kind"] = report.used ? "coarse" : initial ? "given" : "zero";
  if (report.used) {
    cold["harmonics"] = report.harmonics;
    cold["samples"] = report.samples;
    cold["converged"] = report.coarse.converged();
    cold["iterations"] = report.coarse.iterations;
    cold["retried_from_zero"] = report.retried_from_zero;
  }
  d["cold_start"] = cold;
  if (!tried.attempts.empty()) {
    py::list attempts;
    for (const FallbackAttempt& a : tried.attempts) {
      py::dict one;
      one["step"] = a.step;
      one["solver"] = a.result.solver;
      one["termination"] = terminationName(a.result.termination);
      one["iterations"] = a.result.iterations;
      one["residual_norm"] = a.result.final_norm;
      attempts.append(one);
    }
    py::dict f;
    f["taken"] = tried.taken.empty() ? py::object(py::none()) : py::object(py::str(tried.taken));
    f["attempts"] = attempts;
    f["seconds"] = tried.seconds;
    d["fallback"] = f;
    d["seconds"] = d["seconds"].cast<double>() + tried.seconds;
  }
  d["system"] = system;
  d["unknowns"] = hb->size();
  d["omega"] = model.omega;
  d["solution"] = solutionDict(model, hb->fullCoefficients(result.solution));
  return d;
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
  HillResult hill;
  {
    py::gil_scoped_release unlocked;
    hill = hillStability(model, full);
  }
  std::vector<std::complex<double>> multipliers, exponents;
  for (const auto& e : hill.exponents) {
    multipliers.push_back(e.multiplier);
    exponents.push_back(e.exponent);
  }
  py::dict d;
  d["stable"] = hill.stable;
  d["spectral_radius"] = hill.spectral_radius;
  d["multipliers"] = multipliers;
  d["exponents"] = exponents;
  d["pencil_size"] = hill.pencil_size;
  d["seconds"] = hill.seconds;
  d["failure"] = hill.failure;
  return d;
}

py::dict sweep(const PyModel& m, std::optional<double> from, std::optional<double> to, std::optional<double> given_step,
               const std::string& method, std::optional<int> harmonics, std::optional<int> samples,
               const std::string& solver_name, const std::string& system, double tolerance, int max_iterations,
               int max_evaluations, double time_limit, const std::map<std::string, std::string>& backend,
               int max_points, const std::string& fallback) {
  const HbModel model = withSettings(m.scene.model, std::nullopt, harmonics, samples);
  if (method != "sequential" && method != "arclength")
    throwInputError("method", "\"" + method + "\"", "must be \"sequential\" or \"arclength\"");
  ContinuationOptions options;
  if (!from && !m.scene.sweep_from) throwInputError("start", "(missing)", "the model has no sweep range: give start and stop");
  options.from = from ? *from : *m.scene.sweep_from;
  options.to = to ? *to : m.scene.sweep_to.value_or(options.from);
  const double step = given_step ? *given_step
                                 : ContinuationOptions::defaultStep(options.from, options.to, method == "arclength");
  options.step = step;
  options.min_step = std::min(1e-6, step);
  options.max_step = std::max(1.0, step);
  options.max_points = max_points;
  options.condensed = condensedSystem(system);
  options.validate();
  const SolverOptions solver_options = solverOptions(tolerance, max_iterations, max_evaluations, time_limit, backend);
  auto solver = makeSolver(solver_name);
  const OwnedFallbackChain fallbacks(fallback, solver_name, "fallback");
  options.fallbacks = fallbacks.chain();
  Curve curve;
  {
    py::gil_scoped_release unlocked;
    curve = method == "arclength" ? sweepArclength(model, *solver, solver_options, options)
                                  : sweepSequential(model, *solver, solver_options, options);
  }
  py::dict d = curveDict(model, curve);
  d["solver"] = solver->name();
  d["method"] = method;
  d["system"] = system;
  return d;
}

py::dict simulate(const PyModel& m, std::optional<double> omega, double step, int periods, double theta,
                  double periodic_tolerance, double restitution, const std::optional<Eigen::VectorXd>& initial) {
  const HbModel model = withSettings(m.scene.model, omega, std::nullopt, std::nullopt);
  TimeOptions options;
  options.step = step;
  options.max_periods = periods;
  options.theta = theta;
  options.periodic_tolerance = periodic_tolerance;
  options.restitution = restitution;
  options.validate();
  Eigen::VectorXd start;
  if (initial) {
    const Eigen::Index full_size = static_cast<Eigen::Index>(model.basis.size()) *
                                   (model.structure.dofs() + model.lawComponents());
    if (initial->size() != full_size || !initial->allFinite())
      throwInputError("initial", "(" + std::to_string(initial->size()) + " values)",
                      "must be a finite full coefficient vector of " + std::to_string(full_size) + " values");
    start = *initial;
  }
  TimeReference reference;
  {
    py::gil_scoped_release unlocked;
    reference = integrateToSteadyState(model, options, start);
  }
  return referenceDict(model, reference);
}

// The exact periodic orbit by shooting (Coulomb 1D, Jenkins on one DOF and
// Signorini laws in closed form; cubic, planar Coulomb and Stribeck by the smooth-phase flow),
// started from the harmonic-balance solution at the same ω, with its Floquet
// multipliers and one period sampled on N instants.
py::dict shoot(const PyModel& m, std::optional<double> omega, std::optional<int> harmonics,
               std::optional<int> samples, const std::string& solver_name, double restitution, double tolerance,
               int max_iterations, double time_limit) {
  const HbModel model = withSettings(m.scene.model, omega, harmonics, samples);
  orbits::ShootingOptions options;
  options.tolerance = tolerance;
  options.max_iterations = max_iterations;
  options.time_limit = time_limit;
  options.validate();
  // time_limit bounds the whole call: the harmonic-balance start, then shooting with what is left.
  const Deadline deadline(time_limit);
  const std::unique_ptr<orbits::Flow> flow_owner = orbits::makeFlow(model, restitution);  // rejects other laws first
  const orbits::Flow& flow = *flow_owner;
  auto solver = makeSolver(solver_name);
  auto hb = makeHbSystem(model, true, LinearAlgebra::kAuto, deadline);
  py::dict d;
  orbits::ShootingResult orbit;
  orbits::FlowSamples sampled;
  bool sampled_ok = false;
  SolverResult start;
  {
    py::gil_scoped_release unlocked;
    SolverOptions start_options;
    if (deadline.limited()) start_options.time_limit = std::max(deadline.remaining(), 1e-3);
    start = solver->solve(*hb, Eigen::VectorXd::Zero(hb->size()), start_options);
    if (start.termination == Termination::kTimeLimit)
      throw TimeLimitReached("time limit of " + formatNumber(time_limit) +
                             " s reached during the harmonic-balance start of shooting");
    const Eigen::VectorXd full = hb->fullCoefficients(start.solution);
    if (deadline.limited()) options.time_limit = std::max(deadline.remaining(), 1e-3);
    orbit = orbits::shootFromHarmonicBalance(flow, model, full, options);
    const double t0 = orbit.start_time;
    for (int i = 0; i < model.samples; ++i) sampled.times.push_back(t0 + flow.period() * i / model.samples);
    sampled_ok = flow.integrate(orbit.state, t0, flow.period(), false, &sampled).ok;
  }
  d["converged"] = orbit.converged;
  d["failure"] = orbit.failure;
  d["from_hb"] = resultDict(start);
  d["omega"] = model.omega;
  d["period"] = flow.period();
  d["restitution"] = restitution;
  d["iterations"] = orbit.iterations;
  d["flow_evaluations"] = orbit.flow_evaluations;
  d["period_residual"] = orbit.period_residual;
  d["start_time"] = orbit.start_time;
  d["state"] = python::toArray(orbit.state);
  d["monodromy"] = python::toArray(orbit.monodromy);
  py::array_t<std::complex<double>> multipliers(orbit.multipliers.size());
  std::copy(orbit.multipliers.data(), orbit.multipliers.data() + orbit.multipliers.size(),
            multipliers.mutable_data());
  // Floquet multipliers belong to an orbit: None when none was found.
  d["multipliers"] = orbit.converged ? py::object(multipliers) : py::none();
  d["spectral_radius"] = orbit.converged ? py::object(py::float_(orbit.spectral_radius)) : py::none();
  d["stable"] = orbit.converged ? py::object(py::bool_(orbit.stable)) : py::none();
  d["events"] = orbit.events;
  d["max_abs_x"] = python::toArray(orbit.max_abs);
  d["seconds"] = orbit.seconds;
  if (sampled_ok) {
    d["t"] = py::array_t<double>(sampled.times.size(), sampled.times.data());
    d["x"] = python::toArray(Eigen::MatrixXd(sampled.displacement.transpose()));
    d["v"] = python::toArray(Eigen::MatrixXd(sampled.velocity.transpose()));
    d["lambda"] = python::toArray(Eigen::MatrixXd(sampled.force.transpose()));
  }
  return d;
}

py::list lawList(const HbModel& model) {
  py::list laws;
  for (const auto& l : model.laws) {
    py::list dofs;
    for (int d : l.dofs) dofs.append(d + 1);
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
                    return PyModel{loadScene(path, overrides)};
                  },
                  py::arg("path"), py::arg("overrides") = std::vector<std::string>{},
                  "Loads a scene file; overrides are \"path=value\" strings as for `eqhb --set`.")
      .def_static("_from_text",
                  [](const std::string& text, const std::string& source) { return PyModel{parseScene(text, source)}; },
                  py::arg("text"), py::arg("source"))
      .def_static("_from_arrays", &modelFromArrays, py::arg("text"), py::arg("mass"), py::arg("damping"),
                  py::arg("stiffness"))
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

  m.def("_solve", &solve, py::arg("model"), py::arg("omega"), py::arg("harmonics"), py::arg("samples"),
        py::arg("solver"), py::arg("system"), py::arg("tolerance"), py::arg("max_iterations"),
        py::arg("max_evaluations"), py::arg("time_limit"), py::arg("options"), py::arg("initial"),
        py::arg("cold_start"), py::arg("fallback"));
  m.def("_sweep", &sweep, py::arg("model"), py::arg("start"), py::arg("stop"), py::arg("step"), py::arg("method"),
        py::arg("harmonics"), py::arg("samples"), py::arg("solver"), py::arg("system"), py::arg("tolerance"),
        py::arg("max_iterations"), py::arg("max_evaluations"), py::arg("time_limit"), py::arg("options"),
        py::arg("max_points"), py::arg("fallback"));
  m.def("_stability", &stability, py::arg("model"), py::arg("full"), py::arg("omega"), py::arg("harmonics"),
        py::arg("samples"));
  m.def("_shoot", &shoot, py::arg("model"), py::arg("omega"), py::arg("harmonics"), py::arg("samples"),
        py::arg("solver"), py::arg("restitution"), py::arg("tolerance"), py::arg("max_iterations"),
        py::arg("time_limit"));
  m.def("_simulate", &simulate, py::arg("model"), py::arg("omega"), py::arg("step"), py::arg("periods"),
        py::arg("theta"), py::arg("periodic_tolerance"), py::arg("restitution"), py::arg("initial"));
}
