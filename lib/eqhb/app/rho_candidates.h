// The ρ an accuracy target chooses from: each law's own ρ times kRhoFactors,
// or the scene as given when a common ρ is set or no law has ρ.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eqhb/app/scene_settings.h"
#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb::app {

constexpr double kRhoFactors[] = {1.0, 0.1, 0.01};

struct RhoCandidates {
  std::vector<HbModel> models;   // the scene with every override, ρ scaled
  std::vector<double> factors;   // one per model
  std::vector<std::optional<RhoSetting>> scene_rho;  // per law, nullopt for a law without ρ
};
RhoCandidates rhoCandidates(const SceneSettings& scene);

// The overrides that give every law with ρ its ρ times `factor`.
std::vector<std::string> scaledRhoOverrides(const std::vector<std::optional<RhoSetting>>& scene_rho, double factor);

}  // namespace eqhb::app
