#include "eqhb/app/rho_candidates.h"

#include "eqhb/scenes/law_rho.h"

namespace eqhb::app {

std::vector<std::string> scaledRhoOverrides(const std::vector<std::optional<RhoSetting>>& scene_rho, double factor) {
  std::vector<std::string> out;
  for (size_t l = 0; l < scene_rho.size(); ++l)
    if (scene_rho[l]) out.push_back(scaledRhoOverride(static_cast<int>(l), *scene_rho[l], factor));
  return out;
}

RhoCandidates rhoCandidates(const SceneSettings& s) {
  RhoCandidates out;
  const Scene scene = loadScene(s);
  out.models.push_back(scene.model);
  out.factors.push_back(1.0);
  out.scene_rho = documentRhos(s, s.overrides);
  if (s.rho) {
    // A common ρ fixes every law's: nothing to choose.
    for (auto& r : out.scene_rho)
      if (r) r = RhoSetting(*s.rho);
    return out;
  }
  bool any = false;
  for (const auto& r : out.scene_rho) any = any || r.has_value();
  if (!any) return out;
  for (double factor : kRhoFactors) {
    if (factor == 1.0) continue;
    SceneSettings scaled = s;
    const auto more = scaledRhoOverrides(out.scene_rho, factor);
    scaled.overrides.insert(scaled.overrides.end(), more.begin(), more.end());
    out.models.push_back(loadScene(scaled).model);
    out.factors.push_back(factor);
  }
  return out;
}

}  // namespace eqhb::app
