#include "precision_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/orbits/orbit_refinement.h"
#include "eqhb/scenes/scene.h"
#include "report_number.h"

namespace eqhb::bench {

namespace {

// Errors below this are rounding of the reference, not discretisation.
constexpr double kRoundingLevel = 1e-10;

// The forms that keep the exact law (the regularised ones change the answer).
bool exactForm(const std::string& form) {
  for (const char* f : {"minmax", "projection", "max", "min", "fischer-burmeister"})
    if (form == f) return true;
  return false;
}

bool takesRho(const HbModel& model) { return lawEntry(*model.laws[0].law).takesRho(); }

// The curve's form "aft" stands for the alternating frequency–time
// formulation of the laws that have it (LawEntry::parse_aft).
constexpr const char* kAftForm = "aft";

Scene load(const PrecisionScene& scene, const std::string& form, std::optional<double> rho) {
  std::vector<std::string> overrides = {"harmonic_balance.omega=" + reportNumber(scene.omega, 17)};
  const Scene plain = loadScene(scene.file, overrides);
  if (form == kAftForm)
    for (const auto& o : lawFormulationOverrides(plain.model, kAftForm)) overrides.push_back(o);
  if (!form.empty() && form != kAftForm)
    for (const auto& o : lawOverrides(plain.model, "form", form)) overrides.push_back(o);
  if (rho)
    for (const auto& o : lawOverrides(plain.model, "rho", reportNumber(*rho, 17))) overrides.push_back(o);
  return loadScene(scene.file, overrides);
}

// ρ balancing the law's two arguments on a solution (see RhoPolicy).
double balancedRho(const HbModel& model, const Eigen::VectorXd& full) {
  const HbSolution solution = summarize(model, full);
  double force = 0.0;
  for (const auto& c : solution.forces) force = std::max(force, c.max_abs);
  double other = 0.0;
  for (const auto& attached : model.laws)
    for (int dof : attached.attachment.dofs()) {
      const auto& x = solution.displacements[dof];
      const auto site = piecewiseLinearSite(*attached.law);
      const bool contact = site && site->contact;  // a wall: ρ weighs a gap
      other = std::max(other, contact ? site->gap + x.max_abs : x.max_abs_rate);
    }
  const auto first = piecewiseLinearSite(*model.laws[0].law);
  const bool contact = first && first->contact;
  return contact ? force / other : other / force;
}

struct Timed {
  SolverResult result;
  Eigen::VectorXd full;
  double seconds = 0.0;
};

Timed solveTimed(const HbModel& model, const PrecisionCurve& curve, int start_harmonics, int repeats) {
  auto solver = makeSolver(curve.backend);
  SolverOptions options;
  options.residual_tolerance = 1e-10;
  options.max_iterations = 400;
  Timed out;
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    out.result = solveByHarmonicContinuation(model, *solver, options, start_harmonics, curve.condensed, &out.full);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (times.back() > 1.0) break;
  }
  std::sort(times.begin(), times.end());
  out.seconds = times[times.size() / 2];
  return out;
}

}  // namespace

std::string PrecisionScene::label() const {
  std::ostringstream s;
  s << std::filesystem::path(file).stem().string() << " ω=" << omega;
  if (restitution > 0) s << ", e=" << restitution;
  return s.str();
}

const char* rhoPolicyName(RhoPolicy policy) {
  switch (policy) {
    case RhoPolicy::kFixed: return "fixed";
    case RhoPolicy::kScaled: return "scaled";
    case RhoPolicy::kAdaptive: return "adaptive";
    case RhoPolicy::kNone: return "none";
  }
  return "?";
}

std::string PrecisionCurve::name() const {
  std::string s = form.empty() ? "no form" : form;
  s += std::string(", ρ ") + rhoPolicyName(rho) + ", " + (condensed ? "condensed" : "full") + ", " + backend;
  return refine ? s + (coarse_start ? " + shooting from H0" : " + shooting") : s;
}

std::vector<PrecisionCurve> curvesFor(const HbModel& model, const std::vector<std::string>& backends,
                                      bool harmonic_balance_reference) {
  std::vector<std::string> forms;
  for (const auto& f : lawEntry(*model.laws[0].law).forms)
    if (exactForm(f)) forms.push_back(f);
  if (forms.empty()) forms.push_back("");
  const std::vector<RhoPolicy> policies = takesRho(model)
      ? std::vector<RhoPolicy>{RhoPolicy::kFixed, RhoPolicy::kScaled, RhoPolicy::kAdaptive}
      : std::vector<RhoPolicy>{RhoPolicy::kNone};
  const RhoPolicy base_policy = policies.front();
  // The own dogleg solves contact on the full system (the condensed one
  // stalls on the min form); friction and smooth laws on the condensed one.
  const bool base_condensed = suitsCondensedSystem(model.laws);
  std::vector<PrecisionCurve> curves;
  for (const auto& form : forms)
    for (RhoPolicy rho : policies) curves.push_back({form, rho, base_condensed, "dogleg", false});
  const bool has_aft = static_cast<bool>(lawEntry(*model.laws[0].law).parse_aft);
  if (harmonic_balance_reference) {
    if (has_aft) curves.push_back({kAftForm, base_policy, base_condensed, "dogleg", false});
    return curves;
  }
  for (const auto& backend : backends)
    for (bool condensed : {true, false})
      if (backend != "dogleg" || condensed != base_condensed)
        curves.push_back({forms.front(), base_policy, condensed, backend, false});
  // The alternating frequency–time form has no ρ (the scene's is unused).
  if (has_aft) curves.push_back({kAftForm, base_policy, base_condensed, "dogleg", false});
  for (const auto& form : forms) curves.push_back({form, base_policy, base_condensed, "dogleg", true});
  curves.push_back({forms.front(), base_policy, base_condensed, "dogleg", true, true});
  return curves;
}

std::vector<PrecisionPoint> runCurve(const PrecisionScene& scene, const PrecisionCurve& curve,
                                     const std::vector<int>& harmonics, const ExactOrbit& exact, int repeats) {
  const int first = harmonics.front();
  std::optional<double> adaptive_rho;
  double adaptive_seconds = 0.0;
  if (curve.rho == RhoPolicy::kAdaptive) {
    const HbModel coarse = withHarmonics(load(scene, curve.form, scene.rho).model, first);
    const Timed t = solveTimed(coarse, curve, first, repeats);
    adaptive_seconds = t.seconds;
    if (t.result.converged()) adaptive_rho = balancedRho(coarse, t.full);
  }
  std::vector<PrecisionPoint> points;
  for (int h : harmonics) {
    PrecisionPoint p;
    p.scene = scene.label();
    p.curve = curve;
    p.harmonics = h;
    std::optional<double> rho;
    if (curve.rho == RhoPolicy::kFixed) rho = scene.rho;
    else if (curve.rho == RhoPolicy::kScaled) rho = scene.rho * first / h;
    else if (curve.rho == RhoPolicy::kAdaptive) rho = adaptive_rho;
    if (curve.rho == RhoPolicy::kAdaptive && !adaptive_rho) {
      p.failure = "the solve at H0 that sets the adaptive rho did not converge";
      p.seconds = adaptive_seconds;
      points.push_back(p);
      continue;
    }
    const HbModel model = withHarmonics(load(scene, curve.form, rho).model, h);
    // A coarse start solves at H₀ only; the orbit is projected on `model`'s H.
    const HbModel solved = curve.coarse_start ? withHarmonics(model, first) : model;
    p.samples = solved.samples;
    p.rho = rho.value_or(0.0);
    const Timed t = solveTimed(solved, curve, std::min(h, first), repeats);
    p.seconds = t.seconds + adaptive_seconds;
    p.iterations = t.result.iterations;
    p.converged = t.result.converged();
    Eigen::VectorXd answer = t.full;
    if (!p.converged) p.failure = terminationName(t.result.termination);
    if (p.converged && curve.refine) {
      orbits::RefinementOptions options;
      options.restitution = scene.restitution;
      options.output_harmonics = h;
      const auto refined = orbits::refineByShooting(solved, t.full, options);
      p.seconds += refined.seconds;
      p.converged = refined.converged;
      p.failure = refined.failure;
      answer = refined.full;
    }
    if (p.converged) {
      const SeriesError e = seriesError(model, answer, exact);
      p.sup_error = e.sup;
      p.max_abs_error = e.max_abs;
    }
    points.push_back(p);
  }
  return points;
}

RateFit fitRate(const std::vector<PrecisionPoint>& points) {
  RateFit fit;
  auto slope = [&](auto error_of) -> double {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int count = 0;
    for (const auto& p : points) {
      const double e = error_of(p);
      if (!p.converged || !(e > kRoundingLevel)) continue;
      const double x = std::log(p.harmonics), y = std::log(e);
      sx += x, sy += y, sxx += x * x, sxy += x * y, ++count;
    }
    fit.points = std::max(fit.points, count);
    if (count < 2) return NAN;
    return -(count * sxy - sx * sy) / (count * sxx - sx * sx);
  };
  fit.sup = slope([](const PrecisionPoint& p) { return p.sup_error; });
  fit.max_abs = slope([](const PrecisionPoint& p) { return p.max_abs_error; });
  return fit;
}

}  // namespace eqhb::bench
