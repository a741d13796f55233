// signorini: unilateral contact with a rigid wall (laws/signorini.h).
#include "eqhb/laws/registry/entry_support.h"
#include "eqhb/laws/signorini.h"

namespace eqhb {

LawEntry signoriniEntry() {
  LawEntry e = lawEntry("signorini", "rigid wall at x = g0 approached from below (pressure p >= 0, force −p)");
  e.forms = {"min", "fischer-burmeister", "sign-square"};
  e.parameters = withRho({{"gap", "", "finite", "g0, the wall's position"},
                          {"form", "min", "min|fischer-burmeister|sign-square", "complementarity function"}});
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    const double gap = t.number("gap", std::nullopt);
    const RhoSetting rho = t.rho();
    return std::make_shared<Signorini>(gap, parseSignoriniForm(t.form("min")), rho);
  };
  // The own dogleg stalls on the condensed min form from a cold start.
  e.system = LawSystem::kFull;
  e.examples = {{"signorini-min", 1, "gap = 0.4\nform = \"min\"\nrho = 1.5"},
                {"signorini-fb", 1, "gap = 0.4\nform = \"fischer-burmeister\"\nrho = 1.5"},
                {"signorini-signsquare", 1, "gap = 0.4\nform = \"sign-square\"\nrho = 1.5"}};
  e.piecewise_linear_flow = [](const Law& law) -> std::optional<PiecewiseLinearSite> {
    PiecewiseLinearSite site;
    site.contact = true;
    site.gap = static_cast<const Signorini&>(law).gap();
    return site;
  };
  return e;
}

}  // namespace eqhb
