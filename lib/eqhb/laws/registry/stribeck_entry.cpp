// stribeck: friction whose limit falls with the sliding speed (laws/stribeck.h).
#include "eqhb/laws/registry/entry_support.h"
#include "eqhb/laws/stribeck.h"

namespace eqhb {

LawEntry stribeckEntry() {
  LawEntry e = lawEntry("stribeck", "friction on one DOF with a limit falling from μ_s N to μ_d N with the speed");
  e.forms = {"minmax"};
  e.parameters = withRho({{"muN_dynamic", "", ">= 0", "sliding limit μ_d N"},
                          {"muN_static", "", ">= muN_dynamic", "limit at rest μ_s N"},
                          {"v_s", "", "> 0", "decay velocity of the limit"},
                          {"form", "minmax", "minmax", "the only form"}});
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    const double dynamic = t.frictionLimit("muN_dynamic");
    const double stat = t.number("muN_static", std::nullopt);
    if (stat < dynamic)
      t.fail(t.path("muN_static"), formatNumber(stat), "must be >= muN_dynamic = " + formatNumber(dynamic));
    const double v_s = t.positive("v_s", std::nullopt);
    const RhoSetting rho = t.rho();
    t.form("minmax");
    return std::make_shared<Stribeck>(dynamic, stat, v_s, rho);
  };
  e.examples = {{"stribeck", 1, "muN_dynamic = 1.0\nmuN_static = 1.5\nv_s = 0.5\nrho = 0.9"}};
  e.smooth_flow = [](const Law& law) -> std::optional<SmoothFlowSite> {
    const auto& stribeck = static_cast<const Stribeck&>(law);
    SmoothFlowSite site;
    site.kind = SmoothFlowSite::Kind::kStribeck;
    site.coefficient = stribeck.dynamicLimit();
    site.drop = stribeck.staticLimit() - stribeck.dynamicLimit();
    site.v_s = stribeck.slidingVelocity();
    return site;
  };
  return e;
}

}  // namespace eqhb
