#include "scene_arguments.h"

#include <algorithm>

#include "eqhb/error.h"
#include "representable_number.h"

namespace eqhb::cli {

void addSceneOptions(CLI::App* cmd, SceneArguments& a) {
  cmd->add_option("scene", a.scene, "Scene file (problems/*.toml)")->required();
  cmd->add_option("--omega", a.omega, "Forcing frequency ω (overrides harmonic_balance.omega)")
      ->check(representableNumber());
  cmd->add_option("--harmonics", a.harmonics, "Number of harmonics H (odd set: 1,3,..,2H-1; all: 0..H)");
  cmd->add_option("--samples", a.samples,
                  "Time samples N per period (>= 2 k_max + 1; default the scene's, raised in proportion to k_max "
                  "where --harmonics needs more)");
  cmd->add_option("--form", a.form, "Law form, for every law that has it (e.g. minmax, projection, min)");
  cmd->add_option("--rho", a.rho, "Scaling ρ > 0 of every law that has one")->check(representableNumber());
  cmd->add_option("--set", a.overrides, "Override a scene value: PATH=VALUE, e.g. law[0].muN=5");
}

Scene loadSceneWith(const SceneArguments& a) {
  std::vector<std::string> o = a.overrides;
  auto num = [](double x) { return formatNumber(x); };
  if (a.omega) o.push_back("harmonic_balance.omega=" + num(*a.omega));
  if (a.harmonics) {
    o.push_back("harmonic_balance.harmonics=" + std::to_string(*a.harmonics));
    // A scene's N is chosen for its own H: raise it where the new H needs more.
    const bool samples_given = a.samples || std::any_of(a.overrides.begin(), a.overrides.end(), [](const std::string& s) {
                                 return s.rfind("harmonic_balance.samples=", 0) == 0;
                               });
    if (!samples_given) {
      try {
        o.push_back("harmonic_balance.samples=" +
                    std::to_string(samplesForHarmonics(loadScene(a.scene, a.overrides).model, *a.harmonics)));
      } catch (const InputError&) {
        // an H the basis refuses: the load below names it as the scene's field
      }
    }
  }
  if (a.samples) o.push_back("harmonic_balance.samples=" + std::to_string(*a.samples));
  if (a.form || a.rho) {
    // --form and --rho apply to every law that has them: look at the scene first.
    const Scene plain = loadScene(a.scene, a.overrides);
    std::vector<std::string> laws;
    if (a.form) laws = lawOverrides(plain.model, "form", *a.form);
    if (a.rho) {
      const auto rho = lawOverrides(plain.model, "rho", num(*a.rho));
      laws.insert(laws.end(), rho.begin(), rho.end());
    }
    o.insert(o.end(), laws.begin(), laws.end());
    if (laws.empty())
      throwInputError(a.form ? "--form" : "--rho", a.form ? *a.form : num(*a.rho),
                      "no law of the scene takes it");
  }
  return loadScene(a.scene, o);
}

}  // namespace eqhb::cli
