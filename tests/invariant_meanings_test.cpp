// The text output says what each law invariant measures and when it is
// expected to be non-zero: every invariant the shipped scenes' laws report
// has a meaning, printed once per kind after the violations.
#include "eqhb/output/invariant_meanings.h"

#include <gtest/gtest.h>

#include <sstream>

#include "eqhb/app/solve.h"
#include "eqhb/output/solution_text.h"
#include "test_support.h"

namespace eqhb {
namespace {

// Small scenes whose laws cover friction (Coulomb, Jenkins, 2-D, Stribeck,
// in time by AFT), contact (complementarity, penalty, with friction) and a
// smooth law; "aft" solves the Jenkins slider in its AFT formulation.
const std::pair<const char*, const char*> kScenes[] = {
    {"friction-1d.toml", ""}, {"contact.toml", ""},       {"coulomb-oscillator.toml", ""},
    {"jenkins-1d.toml", ""},  {"jenkins-1d.toml", "aft"}, {"cubic.toml", ""},
    {"friction-2d.toml", ""}, {"penalty-contact.toml", ""}, {"contact-friction-2d.toml", ""},
    {"stribeck.toml", ""}};

TEST(InvariantMeanings, EveryInvariantOfTheShippedLawsIsExplainedInTheText) {
  int kinds = 0;
  for (const auto& [file, formulation] : kScenes) {
    app::SceneSettings settings;
    settings.path = test::problem(file);
    if (*formulation) settings.formulation = formulation;
    const app::Solution s = app::solve(settings, app::SolveOptions());
    std::ostringstream text;
    output::writeSolutionText(text, s);
    for (const auto& report : s.invariants)
      for (const auto& [name, value] : report.violations) {
        const std::string meaning = output::invariantMeaning(name);
        EXPECT_FALSE(meaning.empty()) << file << ": " << name << " has no meaning";
        EXPECT_NE(text.str().find("    " + name + ": " + meaning + "\n"), std::string::npos) << text.str();
        ++kinds;
      }
  }
  EXPECT_GE(kinds, 20);
}

TEST(InvariantMeanings, SlidingForceErrorIsCalledRingingNotFailure) {
  EXPECT_NE(output::invariantMeaning("sliding_force_error").find("Gibbs ringing"), std::string::npos);
  EXPECT_NE(output::invariantMeaning("aft_force_error").find("stays non-zero at convergence"), std::string::npos);
  EXPECT_EQ(output::invariantMeaning("no_such_invariant"), "");
  std::ostringstream out;
  LawInvariants a{0, "coulomb-1d", {{"sliding_force_error", 0.44}, {"force_limit_excess", 0.0}}};
  LawInvariants b{1, "coulomb-1d", {{"sliding_force_error", 0.3}}};
  output::writeInvariantMeanings(out, {a, b});
  const std::string text = out.str();
  // One line per kind, in the order first met.
  EXPECT_EQ(text.find("sliding_force_error:"), text.rfind("sliding_force_error:"));
  EXPECT_LT(text.find("sliding_force_error:"), text.find("force_limit_excess:"));
  std::ostringstream none;
  output::writeInvariantMeanings(none, {});
  EXPECT_EQ(none.str(), "");
}

}  // namespace
}  // namespace eqhb
