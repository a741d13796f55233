#include "accuracy_options.h"

#include <cmath>

#include "eqhb/error.h"
#include "eqhb/scenes/law_rho.h"

namespace eqhb::cli {

void addAccuracyOptions(CLI::App* cmd, AccuracyArguments& a) {
  cmd->add_flag("--error-estimate", a.error_estimate,
                "Estimate the relative error of max|x| by one more solve at 2H (costs that solve)");
  cmd->add_option("--accuracy", a.tolerance,
                  "Choose the cheapest H (doubling from --harmonics or 5, N following H) and, unless --rho is "
                  "given, rho (each law's times 1, 0.1 or 0.01) whose estimated relative error of max|x| is <= TOL");
  cmd->add_option("--max-harmonics", a.max_harmonics, "With --accuracy: the largest H solved")->capture_default_str();
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
    ladder.push_back(rung);
  }
  return ladder;
}
}  // namespace

nlohmann::json accuracyJson(const AccuracyChoice& c, double tolerance, const std::vector<double>& factors) {
  nlohmann::json out = {{"tolerance", tolerance}, {"reached", c.reached}, {"seconds", c.seconds},
                        {"ladder", ladderJson(c.ladder)}};
  if (!c.reached) out["failure"] = c.failure;
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

std::vector<std::string> scaledRhoOverrides(const std::vector<std::optional<RhoSetting>>& scene_rho, double factor) {
  std::vector<std::string> out;
  for (size_t l = 0; l < scene_rho.size(); ++l)
    if (scene_rho[l]) out.push_back(scaledRhoOverride(static_cast<int>(l), *scene_rho[l], factor));
  return out;
}

RhoCandidates rhoCandidates(const SceneArguments& a) {
  RhoCandidates out;
  const Scene scene = loadSceneWith(a);
  out.models.push_back(scene.model);
  out.factors.push_back(1.0);
  out.scene_rho = lawRhos(a.scene, a.overrides);
  if (a.rho) {
    // --rho fixes every law's ρ: nothing to choose.
    for (auto& r : out.scene_rho)
      if (r) r = RhoSetting(*a.rho);
    return out;
  }
  bool any = false;
  for (const auto& r : out.scene_rho) any = any || r.has_value();
  if (!any) return out;
  for (double factor : kRhoFactors) {
    if (factor == 1.0) continue;
    SceneArguments scaled = a;
    const auto more = scaledRhoOverrides(out.scene_rho, factor);
    scaled.overrides.insert(scaled.overrides.end(), more.begin(), more.end());
    out.models.push_back(loadSceneWith(scaled).model);
    out.factors.push_back(factor);
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

}  // namespace eqhb::cli
