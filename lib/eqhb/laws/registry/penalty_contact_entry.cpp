// penalty-contact: an elastic wall, p = k_n max(0, x − g0) (laws/penalty_contact.h).
#include "eqhb/laws/penalty_contact.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

LawEntry penaltyContactEntry() {
  LawEntry e = lawEntry("penalty-contact",
                        "elastic wall at x = g0 approached from below: pressure k_n max(0, x − g0), force −p");
  e.parameters = {{"stiffness", "", "> 0", "k_n, the wall's stiffness"},
                  {"gap", "", "finite", "g0, the wall's position"}};
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    const double stiffness = t.positive("stiffness", std::nullopt);
    return std::make_shared<PenaltyContact>(stiffness, t.number("gap", std::nullopt));
  };
  e.examples = {{"penalty-contact", 1, "stiffness = 3.0\ngap = 0.4"},
                {"penalty-contact-stiff", 1, "stiffness = 200.0\ngap = -0.3"}};
  e.piecewise_linear_flow = [](const Law& law) -> std::optional<PiecewiseLinearSite> {
    const auto& wall = static_cast<const PenaltyContact&>(law);
    PiecewiseLinearSite site;
    site.contact = true;
    site.gap = wall.gap();
    site.penalty = wall.stiffness();
    return site;
  };
  return e;
}

}  // namespace eqhb
