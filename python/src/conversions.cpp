#include "conversions.h"

#include <cmath>
#include <complex>
#include <cstdint>

#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/invariants.h"
#include "eqhb/output/orbit_json.h"
#include "eqhb/output/simulation_json.h"
#include "eqhb/output/solution_json.h"
#include "eqhb/output/sweep_output.h"

namespace eqhb::python {

py::array_t<double> toArray(const Eigen::VectorXd& v) {
  py::array_t<double> a(v.size());
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

py::array_t<double> toArray(const Eigen::MatrixXd& m) {
  py::array_t<double> a({m.rows(), m.cols()});
  auto view = a.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  return a;
}

namespace {

// cos and sin coefficients of every channel, one row per channel.
void splitCoefficients(const HarmonicSet& basis, const std::vector<ChannelSummary>& channels,
                       Eigen::MatrixXd& cos, Eigen::MatrixXd& sin) {
  const int h = static_cast<int>(basis.harmonics().size());
  cos.setZero(static_cast<Eigen::Index>(channels.size()), h);
  sin.setZero(static_cast<Eigen::Index>(channels.size()), h);
  for (size_t c = 0; c < channels.size(); ++c)
    for (int j = 0; j < h; ++j) {
      const int o = basis.offset(j);
      cos(c, j) = channels[c].coefficients[o];
      if (basis.harmonics()[j] != 0) sin(c, j) = channels[c].coefficients[o + 1];
    }
}

Eigen::MatrixXd samples(const std::vector<ChannelSummary>& channels, int n) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(channels.size()), n);
  for (size_t c = 0; c < channels.size(); ++c) m.row(c) = channels[c].samples.transpose();
  return m;
}

}  // namespace

py::dict solutionDict(const HbModel& model, const Eigen::VectorXd& full) {
  return solutionDict(model, full, summarize(model, full));
}

py::dict solutionDict(const HbModel& model, const Eigen::VectorXd& full, const HbSolution& s) {
  py::dict d;
  d["harmonics"] = py::array_t<int>(model.basis.harmonics().size(), model.basis.harmonics().data());
  Eigen::MatrixXd cos, sin;
  splitCoefficients(model.basis, s.displacements, cos, sin);
  d["x_cos"] = toArray(cos);
  d["x_sin"] = toArray(sin);
  splitCoefficients(model.basis, s.forces, cos, sin);
  d["lambda_cos"] = toArray(cos);
  d["lambda_sin"] = toArray(sin);
  Eigen::VectorXd t(model.samples);
  for (int i = 0; i < model.samples; ++i) t[i] = 2 * M_PI / model.omega * i / model.samples;
  d["t"] = toArray(t);
  d["x"] = toArray(samples(s.displacements, model.samples));
  d["lambda"] = toArray(samples(s.forces, model.samples));
  Eigen::VectorXd max_x(s.displacements.size()), max_v(s.displacements.size()), max_l(s.forces.size());
  py::list labels;  // the law components' (HbSolution's labelling)
  for (size_t i = 0; i < s.displacements.size(); ++i) {
    max_x[i] = s.displacements[i].max_abs;
    max_v[i] = s.displacements[i].max_abs_rate;
  }
  for (size_t q = 0; q < s.forces.size(); ++q) {
    max_l[q] = s.forces[q].max_abs;
    labels.append(s.forces[q].label);
  }
  d["max_abs_x"] = toArray(max_x);
  d["max_abs_velocity"] = toArray(max_v);
  d["max_abs_lambda"] = toArray(max_l);
  d["lambda_labels"] = labels;
  py::list invariants;
  for (const auto& report : checkInvariants(model, full)) {
    py::dict violations;
    for (const auto& [name, value] : report.violations) violations[py::str(name)] = value;
    invariants.append(py::dict(py::arg("law") = report.law + 1, py::arg("type") = report.type,
                               py::arg("violations") = violations));
  }
  d["invariants"] = invariants;
  d["full"] = toArray(full);
  return d;
}

py::dict resultDict(const SolverResult& r) {
  py::dict d;
  d["solver"] = r.solver;
  d["converged"] = r.converged();
  d["termination"] = terminationName(r.termination);
  d["native_code"] = r.native_code;
  d["native_message"] = r.native_message;
  d["iterations"] = r.iterations;
  d["residual_evaluations"] = r.residual_evaluations;
  d["jacobian_evaluations"] = r.jacobian_evaluations;
  d["initial_residual_norm"] = r.initial_norm;
  d["residual_norm"] = r.final_norm;
  d["seconds"] = r.seconds;
  return d;
}

py::dict curveDict(const HbModel& model, const Curve& curve) {
  const CurveParts parts = splitCurve(curve);
  const Eigen::Index points = static_cast<Eigen::Index>(parts.converged.size());
  const int dofs = model.structure.dofs();
  const int h = static_cast<int>(model.basis.harmonics().size());
  Eigen::VectorXd omega(points), residual(points), seconds(points), energy(points);
  Eigen::MatrixXd max_abs(points, dofs), first(points, dofs);
  py::array_t<bool> converged(points), fold(points);
  py::array_t<int> iterations(points), evaluations(points);
  py::array_t<double> x_cos({static_cast<py::ssize_t>(points), static_cast<py::ssize_t>(dofs),
                             static_cast<py::ssize_t>(h)});
  py::array_t<double> x_sin({static_cast<py::ssize_t>(points), static_cast<py::ssize_t>(dofs),
                             static_cast<py::ssize_t>(h)});
  auto cos_view = x_cos.mutable_unchecked<3>();
  auto sin_view = x_sin.mutable_unchecked<3>();
  py::list terminations, fallbacks;
  for (Eigen::Index p = 0; p < points; ++p) {
    const CurvePoint& c = *parts.converged[p];
    // A point raised by an accuracy target holds more harmonics: the curve's
    // are its first ones, in blocks of its own size per DOF.
    const int nb = c.harmonics > model.basis.count() ? HarmonicSet(model.basis.kind(), c.harmonics).size()
                                                      : model.basis.size();
    omega[p] = c.omega;
    residual[p] = c.residual_norm;
    seconds[p] = c.seconds;
    energy[p] = c.energy;
    converged.mutable_at(p) = c.converged;
    fold.mutable_at(p) = c.fold;
    iterations.mutable_at(p) = c.iterations;
    evaluations.mutable_at(p) = c.residual_evaluations;
    terminations.append(c.termination);
    fallbacks.append(c.fallback);
    for (int i = 0; i < dofs; ++i) {
      max_abs(p, i) = c.max_abs[i];
      first(p, i) = c.first_harmonic[i];
      for (int j = 0; j < h; ++j) {
        const int o = i * nb + model.basis.offset(j);
        cos_view(p, i, j) = c.full[o];
        sin_view(p, i, j) = model.basis.harmonics()[j] != 0 ? c.full[o + 1] : 0.0;
      }
    }
  }
  py::list failed;
  for (const CurvePoint* c : parts.failed) {
    py::dict f;
    f["omega"] = c->omega;
    f["termination"] = c->termination;
    f["iterations"] = c->iterations;
    f["residual_evaluations"] = c->residual_evaluations;
    f["jacobian_evaluations"] = c->jacobian_evaluations;
    f["residual_norm"] = c->residual_norm;
    f["seconds"] = c->seconds;
    failed.append(f);
  }
  py::dict d;
  d["omega"] = toArray(omega);
  d["converged"] = converged;
  d["termination"] = terminations;
  d["fallback"] = fallbacks;  // per point: the fallback step that converged it, "" if none was needed
  d["iterations"] = iterations;
  d["residual_evaluations"] = evaluations;
  d["residual_norm"] = toArray(residual);
  d["seconds_per_point"] = toArray(seconds);
  d["max_abs"] = toArray(max_abs);
  d["first_harmonic"] = toArray(first);
  d["energy"] = toArray(energy);
  d["fold"] = fold;
  d["harmonics"] = py::array_t<int>(model.basis.harmonics().size(), model.basis.harmonics().data());
  d["x_cos"] = x_cos;
  d["x_sin"] = x_sin;
  d["failed"] = failed;  // the points that did not converge (output/curve_writers.h: kFailedPointFields)
  d["folds"] = curve.fold_omegas;
  d["complete"] = curve.complete;
  d["stop_reason"] = curve.stop_reason;
  d["failed_points"] = curve.failed_points;
  d["seconds"] = curve.seconds;
  return d;
}

namespace {
// The optional per-point fields of the JSON writer's points, and their names
// in the dict (a point's H and N beside the curve's "harmonics" array).
const std::pair<const char*, const char*> kPointFields[] = {
    {"stable", "stable"},         {"bifurcation", "bifurcation"},   {"spectral_radius", "spectral_radius"},
    {"multipliers", "multipliers"}, {"error_estimate", "error_estimate"}, {"harmonics", "point_harmonics"},
    {"samples", "point_samples"}, {"accuracy_met", "accuracy_met"}, {"accuracy_seconds", "accuracy_seconds"},
    {"accuracy_failure", "accuracy_failure"}, {"accuracy_test", "accuracy_test"}, {"accuracy_error", "accuracy_error"},
    {"stability_method", "stability_method"}, {"stability_note", "stability_note"}};
const char* const kRunFields[] = {"scene",        "solver",       "method",       "from",
                                  "to",           "step",         "system",       "harmonic_set",
                                  "samples",      "bifurcations", "stability_seconds", "solve_seconds",
                                  "rho",          "accuracy",     "dof_labels",   "peak_dof",
                                  "shown",        "stability_time_limited", "stability_points_analysed"};

py::object pointValue(const std::string& key, const nlohmann::json& value) {
  if (key != "multipliers") return fromJson(value);
  py::list out;  // [re, im] pairs as complex numbers
  for (const auto& m : value) out.append(std::complex<double>(m[0].get<double>(), m[1].get<double>()));
  return std::move(out);
}
}  // namespace

py::dict sweepDict(const app::SweepResult& r) {
  const nlohmann::json j = output::sweepJson(r);
  py::dict d = curveDict(r.model, r.curve);
  for (const char* key : kRunFields)
    if (j.contains(key)) d[key] = fromJson(j[key]);
  const nlohmann::json& points = j["points"];
  for (const auto& [key, name] : kPointFields) {
    bool any = false;
    for (const auto& p : points) any = any || p.contains(key);
    if (!any) continue;
    py::list values;  // None where a point has no such value
    for (const auto& p : points) values.append(p.contains(key) ? pointValue(key, p[key]) : py::none());
    d[name] = values;
  }
  return d;
}

py::dict referenceDict(const HbModel& model, const TimeReference& ref) {
  py::dict d;
  d["periodic"] = ref.periodic;
  d["periods"] = ref.periods;
  d["step"] = ref.step;
  d["steps_per_period"] = ref.steps_per_period;
  d["periodicity_error"] = ref.periodicity_error;
  d["seconds"] = ref.seconds;
  const Eigen::Index n = ref.displacement.rows();
  Eigen::VectorXd t(n);
  for (Eigen::Index i = 0; i < n; ++i) t[i] = 2 * M_PI / model.omega * i / ref.steps_per_period;
  d["t"] = toArray(t);
  // One row per DOF / law component, as in the harmonic-balance solutions.
  d["x"] = toArray(Eigen::MatrixXd(ref.displacement.transpose()));
  d["v"] = toArray(Eigen::MatrixXd(ref.velocity.transpose()));
  d["lambda"] = toArray(Eigen::MatrixXd(ref.force.transpose()));
  d["max_abs_x"] = toArray(Eigen::VectorXd(ref.displacement.cwiseAbs().colwise().maxCoeff().transpose()));
  d["coefficients"] = solutionDict(model, ref.coefficients);
  return d;
}

py::object fromJson(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null: return py::none();
    case nlohmann::json::value_t::boolean: return py::bool_(v.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(v.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(v.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: return py::float_(v.get<double>());
    case nlohmann::json::value_t::string: return py::str(v.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const auto& item : v) out.append(fromJson(item));
      return std::move(out);
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, item] : v.items()) out[py::str(key)] = fromJson(item);
      return std::move(out);
    }
    default: return py::none();
  }
}

namespace {
py::array_t<std::complex<double>> complexArray(const std::vector<std::complex<double>>& values) {
  py::array_t<std::complex<double>> out(values.size());
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}
}  // namespace

py::dict stabilityDict(const HillResult& hill) {
  py::dict d = fromJson(output::stabilityJson(hill));
  std::vector<std::complex<double>> multipliers, exponents;
  for (const auto& e : hill.exponents) {
    multipliers.push_back(e.multiplier);
    exponents.push_back(e.exponent);
  }
  d["multipliers"] = complexArray(multipliers);
  d["exponents"] = complexArray(exponents);
  d["failure"] = hill.failure;  // empty when computed
  return d;
}

py::dict solveDict(const app::Solution& s) {
  py::dict d = fromJson(output::solutionJson(s, false));
  if (s.stability) d["stability"] = stabilityDict(*s.stability);
  d["solution"] = solutionDict(s.reported, s.full, s.summary);
  d["warnings"] = s.run.warnings;
  return d;
}

py::dict orbitDict(const app::Orbit& o) {
  py::dict d = fromJson(output::orbitJson(o, false));
  const orbits::ShootingResult& orbit = o.orbit;
  py::dict from_hb = resultDict(o.hb.result);
  from_hb["harmonics"] = o.model().basis.count();
  from_hb["cold_start"] = fromJson(output::coldStartJson(o.hb.cold_start, o.hb.start));
  if (!o.hb.fallback.attempts.empty()) from_hb["fallback"] = fromJson(output::fallbackJson(o.hb.fallback));
  d["from_hb"] = from_hb;
  d["failure"] = orbit.failure;
  d["state"] = toArray(orbit.state);
  d["monodromy"] = toArray(orbit.monodromy);
  const std::vector<std::complex<double>> multipliers(orbit.multipliers.data(),
                                                      orbit.multipliers.data() + orbit.multipliers.size());
  // Floquet multipliers belong to an orbit: None when none was found.
  d["multipliers"] = orbit.converged ? py::object(complexArray(multipliers)) : py::none();
  d["max_abs_x"] = toArray(orbit.max_abs);
  d["lambda_labels"] = lawComponentLabels(o.model());
  d["warnings"] = o.hb.warnings;
  if (o.samples) {
    d["t"] = py::array_t<double>(o.samples->times.size(), o.samples->times.data());
    d["x"] = toArray(Eigen::MatrixXd(o.samples->displacement.transpose()));
    d["v"] = toArray(Eigen::MatrixXd(o.samples->velocity.transpose()));
    d["lambda"] = toArray(Eigen::MatrixXd(o.samples->force.transpose()));
  }
  return d;
}

py::dict simulationDict(const app::Simulation& s) {
  py::dict d = referenceDict(s.model(), s.reference);
  py::dict json = fromJson(output::simulationJson(s, false));
  for (auto item : json)
    if (!d.contains(item.first)) d[item.first] = item.second;
  d["theta"] = s.options.theta;
  d["periodic_tolerance"] = s.options.periodic_tolerance;
  d["max_periods"] = s.options.max_periods;
  if (s.hb) d["from_hb"] = resultDict(s.hb->result);
  return d;
}

py::dict comparisonDict(const app::Comparison& c) {
  py::dict d = fromJson(output::comparisonJson(c));
  d["hb"]["solver"] = c.hb.result.solver;
  d["solution"] = solutionDict(c.model(), c.hb.full());
  py::dict reference = referenceDict(c.model(), c.reference);
  for (auto item : py::dict(d["reference"]))
    if (!reference.contains(item.first)) reference[item.first] = item.second;
  d["reference"] = reference;
  d["warnings"] = c.hb.warnings;
  return d;
}

}  // namespace eqhb::python
