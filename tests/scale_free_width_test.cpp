// A regularised friction form's width is made of the contact's own scales
// (law.h, kScaleFreeWidthFraction): NLvib's cantilever with dry friction
// (problems/cantilever-friction-si.toml) posed in SI units, in mm/N/ms and
// nondimensional converges the same way in each, to the same answer. With
// the old fixed slope β = 100 (1/velocity) its SI friction is a viscous
// damper over slips of 1e-5 m/s: the solve ends law_violated and says that
// β is the cause.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/laws/coulomb_1d.h"
#include "cantilever_units.h"
#include "test_support.h"

namespace eqhb {
namespace {

using test::Units;
using test::unitSystems;

struct Outcome {
  SolverResult result;
  double tip = 0.0;   // max|x| at the contact's DOF, in metres
  double beta = 0.0;  // the slope in use, in s/m
};

Outcome solveIn(const Units& u, std::vector<std::string> set) {
  const test::UnitsOutcome solved = test::solveCantileverIn(u, 230.0, std::move(set));
  return {solved.result, solved.contact,
          static_cast<const Coulomb1D&>(*solved.law).beta() * u.time / u.length};
}

TEST(ScaleFreeWidth, RegularisedFrictionConvergesAlikeInAnyUnits) {
  for (const char* form : {"tanh", "piecewise"}) {
    const std::string set_form = "law[0].form=\"" + std::string(form) + "\"";
    const Outcome si = solveIn(unitSystems()[0], {set_form});
    ASSERT_TRUE(si.result.converged()) << form << ": " << si.result.summary();
    for (const Units& u : unitSystems()) {
      const Outcome o = solveIn(u, {set_form});
      ASSERT_TRUE(o.result.converged()) << form << " in " << u.name << ": " << o.result.summary();
      // Elsewhere round-off differs, and a solve of ~100 iterations through
      // a sharp transition takes its own path to the same answer.
      if (u.binary) EXPECT_EQ(o.result.iterations, si.result.iterations) << form << " in " << u.name;
      EXPECT_NEAR(o.tip, si.tip, 1e-8 * si.tip) << form << " in " << u.name;
      EXPECT_NEAR(o.beta, si.beta, 1e-9 * si.beta) << form << " in " << u.name;
    }
  }
}

// The slope the fixed default was (β = 100 s/m in SI): the friction force
// stays far below its limit while the contact slips, and the verdict names β.
TEST(ScaleFreeWidth, AFixedSlopeInSiUnitsIsNamedAsTheCause) {
  const Outcome o = solveIn(unitSystems()[0], {"law[0].form=\"tanh\"", "law[0].beta=100"});
  EXPECT_EQ(o.result.termination, Termination::kLawViolated) << o.result.summary();
  EXPECT_NE(o.result.native_message.find("beta = 100 is"), std::string::npos) << o.result.native_message;
  EXPECT_NE(o.result.native_message.find("leave beta unset"), std::string::npos) << o.result.native_message;
}

}  // namespace
}  // namespace eqhb
