// The law registry: every example of every registered law passes the
// conformance checks (law_checks.h) and the odd-symmetry promise; each entry
// declares exactly the keys its parser reads and refuses out-of-range values
// naming the field; unknown names list the known ones; capabilities answer
// for the laws that have them.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/scenes/scene.h"
#include "law_checks.h"
#include "test_support.h"

namespace eqhb {
namespace {

using test::LawCase;

class RegisteredLaw : public ::testing::TestWithParam<LawCase> {};

TEST_P(RegisteredLaw, PointwisePartialsMatchFiniteDifferences) {
  test::expectPointwisePartialsMatch(*GetParam().law, GetParam().label, 3, 300);
}

TEST_P(RegisteredLaw, AssembledJacobiansMatchFiniteDifferences) {
  test::expectAssembledJacobiansMatch(GetParam().law, GetParam().label, 17);
}

TEST_P(RegisteredLaw, BetweenTwoNodesMatchesFiniteDifferencesAndTheGroundedLaw) {
  test::expectBetweenNodesMatches(GetParam().law, GetParam().label, 41);
}

TEST_P(RegisteredLaw, IsOfItsEntrysType) { EXPECT_EQ(GetParam().law->type(), GetParam().type); }

INSTANTIATE_TEST_SUITE_P(AllLaws, RegisteredLaw, ::testing::ValuesIn(test::registeredExamples()),
                         [](const auto& info) {
                           std::string name = info.param.label;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

// Half-wave sampling of the assembly relies on it (Law::oddSymmetric): a law
// that claims to be odd gives −Ψ and the same partials for negated inputs,
// bit for bit, also on its kinks (v = 0, λ = ±μN, the trial force on the
// limit) where a one-sided comparison would break the symmetry.
TEST(LawSymmetry, OddLawsAreOddBitForBit) {
  const double edges[] = {0.0, 1.3, -1.3, 1.5, -1.5, 1.2, 0.8, 1.04, 0.5, 1.0};
  int odd = 0;
  for (const LawCase& c : test::registeredExamples()) {
    if (!c.law->oddSymmetric()) continue;
    ++odd;
    const int d = c.law->dimension(), n = 400;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    std::uniform_int_distribution<int> pick(0, 9);
    LawSamples s, m;
    s.resize(n, d);
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a) {  // half the samples on kink values
        auto draw = [&] { return i % 2 ? u(rng) : edges[pick(rng)]; };
        s.displacement(i, a) = draw();
        s.velocity(i, a) = draw();
        s.force(i, a) = draw();
        s.force_rate(i, a) = draw();
      }
    m = s;
    m.displacement = -s.displacement;
    m.velocity = -s.velocity;
    m.force = -s.force;
    m.force_rate = -s.force_rate;
    c.law->evaluate(s, true);
    c.law->evaluate(m, true);
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a) {
        ASSERT_EQ(m.psi(i, a), -s.psi(i, a)) << c.label << " sample " << i;
        for (int b = 0; b < d; ++b) {
          const int ab = a * d + b;
          if (c.law->usesDisplacement()) { ASSERT_EQ(m.dpsi_ddisplacement(i, ab), s.dpsi_ddisplacement(i, ab)) << c.label; }
          if (c.law->usesVelocity()) { ASSERT_EQ(m.dpsi_dvelocity(i, ab), s.dpsi_dvelocity(i, ab)) << c.label; }
          ASSERT_EQ(m.dpsi_dforce(i, ab), s.dpsi_dforce(i, ab)) << c.label << " sample " << i;
          if (c.law->usesForceRate()) { ASSERT_EQ(m.dpsi_dforce_rate(i, ab), s.dpsi_dforce_rate(i, ab)) << c.label; }
        }
      }
  }
  EXPECT_GE(odd, 14);  // Coulomb 1D/2D in every form, Stribeck, cubic, Jenkins
}

TEST(LawRegistry, EveryLawHasExamplesAndItsFormsAreCovered) {
  ASSERT_GE(lawRegistry().size(), 7u);
  for (const LawEntry& entry : lawRegistry()) {
    EXPECT_FALSE(entry.examples.empty()) << entry.type;
    EXPECT_FALSE(entry.summary.empty()) << entry.type;
    EXPECT_TRUE(entry.parse || entry.parse_aft) << entry.type;
    for (const auto& form : entry.forms) {
      bool covered = false;
      for (const auto& example : entry.examples)
        covered = covered || example.keys.find("form = \"" + form + "\"") != std::string::npos;
      // A single form is the default one, covered without naming it.
      EXPECT_TRUE(covered || entry.forms.size() == 1) << entry.type << " form " << form;
    }
  }
}

// The unknown-key message lists the keys the parser asked about: they must
// be the declared parameters (plus the keys every law has: `formulation` is
// read for every law, law_registry.h's parseLaw).
TEST(LawRegistry, DeclaredParametersAreTheKeysTheParserReads) {
  for (const LawEntry& entry : lawRegistry())
    for (const LawExample& example : entry.examples) {
      std::set<std::string> keys = {"type", "between", "dofs", "nodes", "formulation"};
      for (const auto& p : entry.parameters) keys.insert(p.key);
      std::string allowed;
      for (const auto& k : keys) allowed += (allowed.empty() ? "" : ", ") + k;
      try {
        parseScene(test::exampleScene(entry, example, "not_a_key = 1"), example.label);
        ADD_FAILURE() << example.label << ": an unknown key was accepted";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("law[0].not_a_key = 1: unknown key (allowed here: " + allowed + ")"),
                  std::string::npos)
            << example.label << ": " << e.what();
      }
    }
}

// A declared lower bound is enforced with a message naming the field.
TEST(LawRegistry, ValuesBelowTheDeclaredRangeAreRefusedNamingTheField) {
  int checked = 0;
  for (const LawEntry& entry : lawRegistry())
    for (const LawParameter& p : entry.parameters) {
      if (p.range.rfind(">", 0) != 0) continue;
      const LawExample& example = entry.examples.front();
      try {
        parseScene(test::exampleScene(entry, example), example.label, {"law[0]." + p.key + "=-1"});
        ADD_FAILURE() << entry.type << "." << p.key << " = -1 was accepted (range " << p.range << ")";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("law[0]." + p.key), std::string::npos) << e.what();
        ++checked;
      }
    }
  EXPECT_GE(checked, 20);
}

TEST(LawRegistry, UnknownTypesListTheKnownOnes) {
  EXPECT_EQ(findLaw("coulomb-3d"), nullptr);
  const LawEntry& entry = *findLaw("coulomb-1d");
  const std::string text =
      test::exampleScene(entry, entry.examples.front());
  try {
    parseScene(std::string(text).replace(text.find("coulomb-1d"), 10, "coulomb-3d"), "scene");
    ADD_FAILURE() << "an unknown law type was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("law[0].type = \"coulomb-3d\": unknown law (known: " + knownLawTypes() + ")"),
              std::string::npos)
        << message;
    for (const LawEntry& known : lawRegistry()) EXPECT_NE(message.find(known.type), std::string::npos);
  }
}

TEST(LawRegistry, CapabilitiesAnswerForTheLawsThatHaveThem) {
  for (const LawCase& c : test::registeredExamples()) {
    const auto smooth = smoothFlowSite(*c.law);
    const auto piecewise = piecewiseLinearSite(*c.law);
    const bool jenkins_1d = c.type == "jenkins" && c.law->dimension() == 1;
    EXPECT_EQ(smooth.has_value(), c.type == "coulomb-1d" || c.type == "coulomb-2d" || c.type == "stribeck" ||
                                      c.type == "cubic" || c.type == "polynomial" || c.type == "quadratic-damping")
        << c.label;
    if (smooth && smooth->kind == SmoothFlowSite::Kind::kForce) {
      // The exact flow's force is the law's: f(x, ẋ) = −Ψ(x, ẋ, λ = 0), with
      // its partials against central differences.
      for (double x : {-1.3, -0.2, 0.7, 1.6})
        for (double v : {-0.9, 0.4, 1.1}) {
          LawSamples samples;
          samples.resize(1, 1);
          samples.displacement(0, 0) = x;
          samples.velocity(0, 0) = v;
          samples.force(0, 0) = 0.0;
          c.law->evaluate(samples, false);
          double f = 0.0, df_dx = 0.0, df_dv = 0.0, fp = 0.0, fm = 0.0, unused = 0.0;
          smooth->force(x, v, &f, &df_dx, &df_dv);
          EXPECT_NEAR(f, -samples.psi(0, 0), 1e-14 * (1.0 + std::abs(f))) << c.label;
          const double h = 1e-6;
          smooth->force(x + h, v, &fp, &unused, &unused);
          smooth->force(x - h, v, &fm, &unused, &unused);
          EXPECT_NEAR(df_dx, (fp - fm) / (2 * h), 1e-6 * (1.0 + std::abs(df_dx))) << c.label;
          smooth->force(x, v + h, &fp, &unused, &unused);
          smooth->force(x, v - h, &fm, &unused, &unused);
          EXPECT_NEAR(df_dv, (fp - fm) / (2 * h), 1e-6 * (1.0 + std::abs(df_dv))) << c.label;
        }
    }
    EXPECT_EQ(piecewise.has_value(),
              c.type == "coulomb-1d" || c.type == "signorini" || c.type == "penalty-contact" || jenkins_1d)
        << c.label;
    if (piecewise) {
      EXPECT_EQ(piecewise->contact, c.type == "signorini" || c.type == "penalty-contact") << c.label;
      EXPECT_EQ(piecewise->rigidWall(), c.type == "signorini") << c.label;
      EXPECT_EQ(piecewise->stiffness > 0.0, jenkins_1d) << c.label;
    }
  }
  EXPECT_EQ(findLaw("signorini")->system, LawSystem::kFull);
  EXPECT_EQ(findLaw("coulomb-1d")->system, LawSystem::kCondensed);
  EXPECT_FALSE(findLaw("cubic")->takesRho());
  EXPECT_TRUE(findLaw("jenkins")->takesRho());
}

}  // namespace
}  // namespace eqhb
