#include "case_verdict.h"

#include <gtest/gtest.h>

namespace eqhb::bench {
namespace {

Case converged(const std::string& solver, const std::string& system, double error_reference, double error_high_h,
               double seconds = 1e-3) {
  Case c;
  c.study = "scenes";
  c.scene = "damper";
  c.form = "minmax";
  c.solver = solver;
  c.system = system;
  c.harmonics = 10;
  c.converged = true;
  c.median_seconds = seconds;
  c.error_reference = error_reference;
  c.error_high_h = error_high_h;
  return c;
}

TEST(CaseVerdict, AConvergedAnswerFarFromBothReferencesIsDisagreeing) {
  // The damper's ipopt-square answer: converged, 37 away from the time reference.
  EXPECT_EQ(verdictOf(converged("ipopt-square", "full", 37.0, 12.0)), Verdict::kDisagrees);
  EXPECT_EQ(verdictOf(converged("dogleg", "full", 0.02, 0.5)), Verdict::kSolved);
  EXPECT_EQ(verdictOf(converged("dogleg", "full", NAN, 0.05)), Verdict::kSolved);
  EXPECT_EQ(verdictOf(converged("dogleg", "full", NAN, NAN)), Verdict::kUnchecked);
  Case failed = converged("dogleg", "full", 0.0, 0.0);
  failed.converged = false;
  EXPECT_EQ(verdictOf(failed), Verdict::kFailed);
}

// contact at H = 20 against its exact orbit (e = 1): the reference harmonic
// balance itself is 0.103 away (truncation), and the forms' answers 0.088 to
// 0.103. Judged against max(0.1, 2 x 0.103) they are solved; a spurious
// root is not, and without a known truncation error the tolerance stays 0.1.
TEST(CaseVerdict, ATruncationErrorAboveTheToleranceWidensItToTwiceThatError) {
  EXPECT_EQ(agreementTolerance(NAN), kAgreementTolerance);
  EXPECT_EQ(agreementTolerance(0.03), kAgreementTolerance);
  EXPECT_DOUBLE_EQ(agreementTolerance(0.103), 0.206);
  Case c = converged("dogleg", "condensed", 0.1025, NAN);
  EXPECT_EQ(verdictOf(c), Verdict::kDisagrees);
  c.truncation_error = 0.103;
  EXPECT_EQ(verdictOf(c), Verdict::kSolved);
  c.error_reference = 0.25;  // the plastic-impact orbit's distance: another orbit
  EXPECT_EQ(verdictOf(c), Verdict::kDisagrees);
}

TEST(CaseVerdict, TheDefaultSolvesMostAndDisagreeingDoesNotCount) {
  // fast: converges everywhere, but half its answers are wrong; slow: solves
  // every case; rescue: solves the one case slow misses... none here.
  std::vector<Case> cases = {
      converged("fast", "condensed", 0.01, NAN, 1e-5), converged("fast", "full", 5.0, NAN, 1e-5),
      converged("slow", "condensed", 0.01, NAN, 1e-2), converged("slow", "full", 0.02, NAN, 1e-2),
  };
  DefaultChoice choice = chooseDefault(cases);
  EXPECT_EQ(choice.default_backend, "slow");
  EXPECT_EQ(choice.default_solved, 2);
  EXPECT_EQ(choice.cases, 2);
  EXPECT_EQ(choice.fallback_backend, "");

  // A third scene case that only "fast" solves makes it the fallback, and a
  // tie on cases solved goes to the faster backend.
  Case extra = converged("fast", "full", 0.01, NAN, 1e-5);
  extra.form = "fischer-burmeister";
  Case missed = extra;
  missed.solver = "slow";
  missed.converged = false;
  cases.push_back(extra);
  cases.push_back(missed);
  choice = chooseDefault(cases);
  EXPECT_EQ(choice.default_backend, "fast");  // 2 solved each; fast is faster
  EXPECT_EQ(choice.default_disagreements, 1);
  EXPECT_EQ(choice.fallback_backend, "slow");
  EXPECT_EQ(choice.either_solved, 3);
  EXPECT_EQ(choice.cases, 3);
}

// bench.csv keeps a form with a comma in one column: the scene study's
// "min, friction max" was split in two, shifting every later column, and the
// performance profile in charts.py merged it with the "min" form.
TEST(CaseVerdict, CsvFieldsWithACommaOrQuoteAreQuoted) {
  EXPECT_EQ(csvField("fischer-burmeister"), "fischer-burmeister");
  EXPECT_EQ(csvField("min, friction max"), "\"min, friction max\"");
  EXPECT_EQ(csvField("a \"b\""), "\"a \"\"b\"\"\"");
}

}  // namespace
}  // namespace eqhb::bench
