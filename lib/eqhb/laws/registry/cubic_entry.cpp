// cubic: a cubic spring kept as a DAE (laws/cubic_stiffness.h).
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

LawEntry cubicEntry() {
  LawEntry e = lawEntry("cubic", "cubic spring, force −ε x³ (as the DAE f + ε x³ = 0)");
  e.parameters = {{"epsilon", "", "finite", "ε"}};
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    return std::make_shared<CubicStiffness>(t.number("epsilon", std::nullopt));
  };
  e.examples = {{"cubic", 1, "epsilon = 0.7"}};
  e.smooth_flow = coefficientSite<CubicStiffness>(SmoothFlowSite::Kind::kCubic, &CubicStiffness::epsilon);
  return e;
}

}  // namespace eqhb
