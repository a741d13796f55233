#include "eqhb/app/scene_settings.h"

#include <algorithm>

#include "eqhb/app/static_preload.h"
#include "eqhb/error.h"
#include "eqhb/scenes/law_rho.h"

namespace eqhb::app {

Scene loadDocument(const SceneSettings& s, const std::vector<std::string>& overrides) {
  return s.document ? s.document->load(overrides) : eqhb::loadScene(s.path, overrides);
}

std::vector<std::optional<RhoSetting>> documentRhos(const SceneSettings& s, const std::vector<std::string>& overrides) {
  return s.document ? s.document->law_rhos(overrides) : lawRhos(s.path, overrides);
}

Scene loadScene(const SceneSettings& s) {
  std::vector<std::string> o = s.overrides;
  auto num = [](double x) { return formatNumber(x); };
  if (s.omega) o.push_back("harmonic_balance.omega=" + num(*s.omega));
  if (s.harmonics) {
    o.push_back("harmonic_balance.harmonics=" + std::to_string(*s.harmonics));
    // A scene's N is chosen for its own H: raise it where the new H needs more.
    const bool samples_given = s.samples || std::any_of(s.overrides.begin(), s.overrides.end(), [](const std::string& a) {
                                 return a.rfind("harmonic_balance.samples=", 0) == 0;
                               });
    if (!samples_given) {
      try {
        o.push_back("harmonic_balance.samples=" +
                    std::to_string(samplesForHarmonics(loadDocument(s, s.overrides).model, *s.harmonics)));
      } catch (const InputError&) {
        // an H the basis refuses: the load below names it as the scene's field
      }
    }
  }
  if (s.samples) o.push_back("harmonic_balance.samples=" + std::to_string(*s.samples));
  if (s.form || s.rho) {
    // form and ρ apply to every law that has them: look at the scene first.
    const Scene plain = loadDocument(s, s.overrides);
    std::vector<std::string> laws;
    if (s.form) laws = lawOverrides(plain.model, "form", *s.form);
    if (s.rho) {
      const auto rho = lawOverrides(plain.model, "rho", num(*s.rho));
      laws.insert(laws.end(), rho.begin(), rho.end());
    }
    o.insert(o.end(), laws.begin(), laws.end());
    if (laws.empty())
      throwInputError(s.form ? "form" : "rho", s.form ? *s.form : num(*s.rho), "no law of the scene takes it");
  }
  if (s.formulation) {
    const auto laws = lawFormulationOverrides(loadDocument(s, s.overrides).model, *s.formulation);
    o.insert(o.end(), laws.begin(), laws.end());
  }
  Scene scene = loadDocument(s, o);
  if (s.show) scene.output.shown = resolveDofs(scene.model, *s.show, "show");
  if (s.peak_dof) scene.output.peak = resolveDof(scene.model, *s.peak_dof, "peak_dof");
  settleUnderPreload(scene);
  return scene;
}

}  // namespace eqhb::app
