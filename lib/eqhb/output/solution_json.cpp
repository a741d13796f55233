#include "eqhb/output/solution_json.h"

#include <algorithm>
#include <cmath>

#include "eqhb/output/static_state_json.h"
#include "eqhb/scenes/dof_choice.h"

namespace eqhb::output {

nlohmann::json coefficientsJson(const HarmonicSet& basis, const Eigen::VectorXd& c) {
  nlohmann::json harmonics = nlohmann::json::array(), cos = nlohmann::json::array(),
                 sin = nlohmann::json::array();
  for (size_t h = 0; h < basis.harmonics().size(); ++h) {
    const int k = basis.harmonics()[h], o = basis.offset(static_cast<int>(h));
    harmonics.push_back(k);
    cos.push_back(c[o]);
    sin.push_back(k == 0 ? 0.0 : c[o + 1]);
  }
  return {{"harmonics", harmonics}, {"cos", cos}, {"sin", sin}};
}

nlohmann::json channelsJson(const HbModel& model, const HbSolution& solution) {
  nlohmann::json dofs = nlohmann::json::array();
  for (size_t i = 0; i < solution.displacements.size(); ++i) {
    const auto& c = solution.displacements[i];
    dofs.push_back({{"dof", i + 1}, {"name", c.label}, {"max_abs", c.max_abs}, {"max_abs_velocity", c.max_abs_rate},
                    {"coefficients", coefficientsJson(model.basis, c.coefficients)}});
  }
  nlohmann::json laws = nlohmann::json::array();
  size_t q = 0;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    nlohmann::json components = nlohmann::json::array();
    double max_abs = 0.0;
    for (int a = 0; a < model.laws[l].law->dimension(); ++a, ++q) {
      const auto& c = solution.forces[q];
      nlohmann::json component = {{"max_abs", c.max_abs},
                                  {"coefficients", coefficientsJson(model.basis, c.coefficients)}};
      const LawAttachment& w = model.laws[l].attachment;
      if (w.grounded()) {
        component["dof"] = w.dof(a) + 1;
        component["dof_name"] = dofLabel(model, w.dof(a));
      } else {  // u_a = Σ weight · x_dof
        nlohmann::json reads = nlohmann::json::array();
        for (const AttachmentTerm& term : w.row(a)) reads.push_back({{"dof", term.dof + 1}, {"name", dofLabel(model, term.dof)}, {"weight", term.weight}});
        component["reads"] = reads;
      }
      components.push_back(component);
      max_abs = std::max(max_abs, c.max_abs);
    }
    laws.push_back({{"law", l + 1}, {"type", model.laws[l].law->type()}, {"max_abs", max_abs},
                    {"components", components}});
  }
  return {{"dofs", dofs}, {"laws", laws}};
}

nlohmann::json coldStartJson(const ColdStartReport& r, const std::string& otherwise) {
  nlohmann::json out = {{"kind", r.used ? "coarse" : otherwise}};
  if (!r.used) return out;
  out["harmonics"] = r.harmonics;
  out["samples"] = r.samples;
  out["converged"] = r.coarse.converged();
  out["iterations"] = r.coarse.iterations;
  out["residual_evaluations"] = r.coarse.residual_evaluations;
  out["jacobian_evaluations"] = r.coarse.jacobian_evaluations;
  out["retried_from_zero"] = r.retried_from_zero;
  if (r.retried_from_zero) {
    out["first_attempt"] = {{"termination", terminationName(r.first_attempt.termination)},
                            {"iterations", r.first_attempt.iterations},
                            {"residual_norm", r.first_attempt.final_norm}};
  }
  return out;
}

nlohmann::json fallbackJson(const FallbackReport& report) {
  nlohmann::json attempts = nlohmann::json::array();
  for (const FallbackAttempt& a : report.attempts)
    attempts.push_back({{"step", a.step},
                        {"solver", a.result.solver},
                        {"termination", terminationName(a.result.termination)},
                        {"iterations", a.result.iterations},
                        {"residual_norm", a.result.final_norm},
                        {"seconds", a.result.seconds},
                        {"note", a.note}});
  return {{"taken", report.taken.empty() ? nlohmann::json(nullptr) : nlohmann::json(report.taken)},
          {"attempts", attempts}, {"seconds", report.seconds}};
}

nlohmann::json stabilityJson(const HillResult& hill) {
  nlohmann::json multipliers = nlohmann::json::array(), exponents = nlohmann::json::array();
  for (const auto& e : hill.exponents) {
    multipliers.push_back({e.multiplier.real(), e.multiplier.imag()});
    exponents.push_back({e.exponent.real(), e.exponent.imag()});
  }
  nlohmann::json out = {{"stable", hill.stable},
                        {"spectral_radius", hill.spectral_radius},
                        {"multipliers", multipliers},
                        {"exponents", exponents},
                        {"state_dimension", hill.state_dimension},
                        {"pencil_size", hill.pencil_size},
                        {"eigensolver", hill.sparse ? "sparse" : "dense"},
                        {"seconds", hill.seconds}};
  if (hill.method != "hill") {  // Hill's outputs keep their keys
    out["method"] = hill.method;
    out["eigensolver"] = hill.method;  // the multipliers are a monodromy matrix's eigenvalues
  }
  if (!hill.failure.empty()) out["failure"] = hill.failure;
  if (!hill.note.empty()) out["note"] = hill.note;
  return out;
}

nlohmann::json invariantsJson(const std::vector<LawInvariants>& invariants) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& report : invariants) {
    nlohmann::json measures;
    for (const auto& [name, value] : report.violations) measures[name] = value;
    out.push_back({{"law", report.law + 1}, {"type", report.type}, {"violations", measures}});
  }
  return out;
}

nlohmann::json errorEstimateJson(const ErrorEstimate& e) {
  return {{"max_abs", e.max_abs},
          {"coefficients", e.coefficients},
          {"max_abs_difference", e.max_abs_difference},
          {"factor", e.factor},
          {"method", "solve at 2H"},
          {"refined_harmonics", e.refined_harmonics},
          {"refined_samples", e.refined_samples},
          {"refined_converged", e.available}};
}

namespace {
nlohmann::json ladderJson(const std::vector<AccuracyRung>& rungs) {
  nlohmann::json ladder = nlohmann::json::array();
  for (const auto& r : rungs) {
    nlohmann::json rung = {{"harmonics", r.harmonics}, {"samples", r.samples}, {"converged", r.converged},
                           {"seconds", r.seconds}};
    rung["estimate"] = r.estimated ? nlohmann::json(r.estimate) : nlohmann::json(nullptr);
    // The test of the rung (none for the top rung of an estimate, which is
    // only the solve at 2H of the rung below).
    rung["test"] = r.tested ? nlohmann::json(accuracyTestName(r.test)) : nlohmann::json(nullptr);
    rung["error"] = r.tested ? nlohmann::json(r.error) : nlohmann::json(nullptr);
    if (r.test_seconds > 0.0) rung["test_seconds"] = r.test_seconds;
    if (!r.fallback.empty()) rung["fallback"] = r.fallback;
    ladder.push_back(rung);
  }
  return ladder;
}
}  // namespace

nlohmann::json accuracyJson(const AccuracyChoice& c, double tolerance, const std::vector<double>& factors) {
  nlohmann::json out = {{"tolerance", tolerance}, {"reached", c.reached}, {"seconds", c.seconds},
                        {"ladder", ladderJson(c.ladder)}};
  if (!c.reached) out["failure"] = c.failure;
  // Which test decided and its value: the true error against the exact
  // orbit, or the estimate times its safety factor (rung_test.h).
  const bool tested = c.tested();
  out["test"] = tested ? nlohmann::json(accuracyTestName(c.test)) : nlohmann::json(nullptr);
  out["error"] = tested ? nlohmann::json(c.error) : nlohmann::json(nullptr);
  if (tested && c.test == AccuracyTest::kEstimate) out["safety_factor"] = c.safety_factor;
  if (!c.test_note.empty()) out["test_note"] = c.test_note;
  if (static_cast<size_t>(c.candidate) < factors.size()) out["rho_factor"] = factors[c.candidate];
  if (c.candidate_ladders.size() > 1) {
    nlohmann::json candidates = nlohmann::json::array();
    for (size_t k = 0; k < c.candidate_ladders.size(); ++k)
      candidates.push_back({{"rho_factor", k < factors.size() ? nlohmann::json(factors[k]) : nlohmann::json(nullptr)},
                            {"ladder", ladderJson(c.candidate_ladders[k])}});
    out["rho_candidates"] = candidates;
  }
  return out;
}

nlohmann::json rhoJson(const std::vector<std::optional<RhoSetting>>& scene_rho, double factor) {
  nlohmann::json per_law = nlohmann::json::array();
  nlohmann::json common;
  bool same = true, any = false;
  for (const auto& r : scene_rho) {
    if (!r) {
      per_law.push_back(nullptr);
      continue;
    }
    const double value = r->value * factor;
    const nlohmann::json chosen = r->scale_free ? nlohmann::json{{"rho_factor", value}} : nlohmann::json(value);
    per_law.push_back(chosen);
    if (any && chosen != common) same = false;
    common = chosen;
    any = true;
  }
  if (!any) return "scene";
  return same ? common : per_law;
}

nlohmann::json refinementJson(const orbits::RefinedSolution& refined, const HbSolution& plain, double restitution) {
  nlohmann::json hb_max_abs = nlohmann::json::array(), max_abs = nlohmann::json::array();
  for (const auto& c : plain.displacements) hb_max_abs.push_back(c.max_abs);
  for (int i = 0; i < refined.max_abs.size(); ++i) max_abs.push_back(refined.max_abs[i]);
  nlohmann::json out = {{"method", "shoot"},
                        {"converged", refined.converged},
                        {"period_residual", refined.orbit.period_residual},
                        {"iterations", refined.orbit.iterations},
                        {"flow_evaluations", refined.orbit.flow_evaluations},
                        {"harmonics", refined.basis.count()},
                        {"samples", refined.samples},
                        {"seconds", refined.seconds},
                        {"restitution", restitution},
                        {"hb_max_abs", hb_max_abs},
                        {"max_abs", max_abs}};
  if (!refined.converged) out["failure"] = refined.failure;
  return out;
}

nlohmann::json trajectoryJson(const HbModel& model, const HbSolution& solution, int samples) {
  nlohmann::json t = nlohmann::json::array();
  for (int i = 0; i < samples; ++i) t.push_back(2 * M_PI / model.omega * i / samples);
  nlohmann::json out = {{"t", t}};
  for (const auto* channels : {&solution.displacements, &solution.forces})
    for (const auto& c : *channels)
      out[c.label] = std::vector<double>(c.samples.data(), c.samples.data() + c.samples.size());
  return out;
}

nlohmann::json solutionJson(const app::Solution& s, bool trajectory) {
  const app::HbRun& run = s.run;
  const HbModel& model = s.model();
  const SolverResult& result = run.result;
  const app::LinearAlgebraReport& la = s.linear_algebra;
  nlohmann::json out;
  out["scene"] = run.scene.name;
  out["solver"] = result.solver;
  out["system"] = run.system->condensed() ? "condensed" : "full";
  out["unknowns"] = run.system->size();
  out["omega"] = model.omega;
  out["harmonics"] = model.basis.count();
  out["highest_harmonic"] = model.basis.highest();
  out["harmonic_set"] = HarmonicSet::kindName(model.basis.kind());
  out["samples"] = model.samples;
  out["converged"] = result.converged();
  out["termination"] = terminationName(result.termination);
  out["native_code"] = result.native_code;
  out["native_message"] = result.native_message;
  out["cold_start"] = coldStartJson(run.cold_start, run.start == "coarse" ? "zero" : run.start);
  if (!run.fallback.attempts.empty()) out["fallback"] = fallbackJson(run.fallback);
  out["iterations"] = result.iterations;
  out["residual_evaluations"] = result.residual_evaluations;
  out["jacobian_evaluations"] = result.jacobian_evaluations;
  out["initial_residual_norm"] = result.initial_norm;
  out["residual_norm"] = result.final_norm;
  out["tolerance"] = run.options.residual_tolerance;
  out["seconds"] = run.medianSeconds();
  out["repeats"] = static_cast<int>(run.times.size());
  out["seconds_min"] = run.times.front();
  out["seconds_max"] = run.times.back();
  out["linear_algebra"] = la.sparse_solver ? "sparse" : "dense";
  if (la.condensation) out["condensation"] = la.sparse_factors ? "sparse" : "dense";
  out["setup_seconds"] = run.setup_seconds;
  if (la.condensation) out["factor_mib"] = la.factor_mib;
  out["peak_rss_mib"] = la.peak_rss_mib;
  const nlohmann::json channels = channelsJson(s.reported, s.summary);
  out["dofs"] = channels["dofs"];
  out["shown"] = shownLabels(model, run.scene.output);
  out["laws"] = channels["laws"];
  out["invariants"] = invariantsJson(s.invariants);
  if (run.scene.at_rest) out["preload"] = staticStateJson(model, *run.scene.at_rest);
  if (s.stability) out["stability"] = stabilityJson(*s.stability);
  if (s.accuracy) {
    out["rho"] = rhoJson(s.accuracy->candidates.scene_rho, s.accuracy->rhoFactor());
    out["accuracy"] = accuracyJson(s.accuracy->choice, s.accuracy->tolerance, s.accuracy->candidates.factors);
  }
  if (s.error_estimate) out["error_estimate"] = errorEstimateJson(*s.error_estimate);
  if (s.refinement) out["refinement"] = refinementJson(*s.refinement, s.plain, s.restitution);
  if (trajectory) out["trajectory"] = trajectoryJson(model, s.summary, s.reported.samples);
  return out;
}

}  // namespace eqhb::output

