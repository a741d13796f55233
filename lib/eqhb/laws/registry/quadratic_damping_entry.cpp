// quadratic-damping: a velocity-squared damper (laws/quadratic_damping.h).
#include <cmath>

#include "eqhb/laws/quadratic_damping.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

LawEntry quadraticDampingEntry() {
  LawEntry e = lawEntry("quadratic-damping", "quadratic damper, force −c ẋ|ẋ| (as the DAE f + c ẋ|ẋ| = 0)");
  e.parameters = {{"coefficient", "", ">= 0", "c"}};
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    const double c = t.number("coefficient", std::nullopt);
    if (!(c >= 0.0)) t.fail(t.path("coefficient"), formatNumber(c), "must be >= 0 (a damper dissipates)");
    return std::make_shared<QuadraticDamping>(c);
  };
  e.examples = {{"quadratic-damping", 1, "coefficient = 0.6"}};
  e.smooth_flow = [](const Law& law) -> std::optional<SmoothFlowSite> {
    SmoothFlowSite site;
    site.kind = SmoothFlowSite::Kind::kForce;
    const double c = static_cast<const QuadraticDamping&>(law).coefficient();
    site.force = [c](double, double v, double* f, double* df_dx, double* df_dv) {
      *f = -c * v * std::abs(v);
      *df_dx = 0.0;
      *df_dv = -2.0 * c * std::abs(v);
    };
    return site;
  };
  return e;
}

}  // namespace eqhb
