// elastic-friction: a normal penalty spring and elastic dry friction under
// its varying load, in the alternating frequency-time form only
// (laws/joints/elastic_friction_aft.h).
#include "eqhb/laws/joints/elastic_friction_aft.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

namespace {

// dofs = [normal, tangential (, tangential)], or between two nodes a normal
// and one or two tangents.
std::shared_ptr<Law> parseElasticFriction(LawTable& t) {
  ElasticFrictionParameters p;
  p.mu = t.number("mu", std::nullopt);
  if (!(p.mu >= 0.0)) t.fail(t.path("mu"), formatNumber(p.mu), "friction coefficient must be >= 0");
  p.k_t = t.positive("k_t", std::nullopt);
  p.k_n = t.positive("k_n", std::nullopt);
  p.gap = t.number("gap", 0.0);
  // Between nodes the components are [normal, tangents...]: tangents alone
  // would make the first tangent the normal.
  if (t.componentsKey() == "tangents" && !t.has("normal"))
    t.fail(t.path("normal"), "(missing)", "an elastic-friction element needs its normal besides its tangents");
  if (t.components() != 2 && t.components() != 3)
    t.fail(t.path(t.componentsKey()), t.dofsText(),
           "an elastic-friction law acts on [normal, tangential] or [normal, tangential, tangential]");
  const std::vector<int>& dofs = t.dofs();
  for (size_t a = 1; a < dofs.size(); ++a)
    if (dofs[a] == dofs[0])
      t.fail(t.path("dofs"), std::to_string(dofs[0] + 1), "the normal DOF is also a tangential DOF");
  p.tangents = t.components() - 1;
  return std::make_shared<ElasticFrictionAft>(p);
}

}  // namespace

LawEntry elasticFrictionEntry() {
  LawEntry e = lawEntry("elastic-friction",
                        "penalty contact k_n max(0, u_n - g0) with elastic dry friction (k_t in series with a slider of "
                        "limit mu p(t)) on 1 or 2 tangents (alternating frequency-time form)");
  e.parameters = {{"mu", "", ">= 0", "friction coefficient μ: the slider's limit is μ p(t)"},
                  {"k_t", "", "> 0", "tangential stiffness in series with the slider"},
                  {"k_n", "", "> 0", "normal penalty stiffness: p = k_n max(0, u_n − g0)"},
                  {"gap", "0", "finite", "g0, the wall's position along the normal"}};
  // No equality form: the tangential force is a functional of the history.
  e.parse_aft = parseElasticFriction;
  e.examples = {{"elastic_friction_2d", 2, "mu = 0.4\nk_t = 2.0\nk_n = 3.0\ngap = -0.5"},
                {"elastic_friction_3d", 3, "mu = 0.3\nk_t = 1.5\nk_n = 2.5\ngap = -0.2"}};
  return e;
}

}  // namespace eqhb
