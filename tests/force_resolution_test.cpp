#include "eqhb/harmonic_balance/force_resolution.h"

#include <gtest/gtest.h>

#include <string>

#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

// contact-friction-2d (2 DOFs, one law of 2 components) on H = 40, all
// harmonics: the normal force's channel set by `amplitude(k)` on its cosines.
struct PlanarContact {
  HbModel model = loadScene(test::problem("contact-friction-2d.toml")).model;
  Eigen::VectorXd full;
  explicit PlanarContact(int harmonics = 40) {
    model.basis = HarmonicSet(HarmonicKind::kAll, harmonics);
    model.omega = 0.126;
    full = Eigen::VectorXd::Zero((model.structure.dofs() + model.lawComponents()) * model.basis.size());
  }
  template <class Amplitude>
  void setNormalForce(Amplitude amplitude) {
    const int nb = model.basis.size(), channel = model.structure.dofs() + model.componentIndex(0, 0);
    for (size_t h = 0; h < model.basis.harmonics().size(); ++h) {
      const int k = model.basis.harmonics()[h];
      if (k > 0) full[channel * nb + model.basis.offset(static_cast<int>(h))] = amplitude(k);
    }
  }
};

// A kinked or jumping force (a square wave's 1/k) is resolved: its middle
// harmonics outweigh its top ones.
TEST(ForceResolution, AFallingSpectrumIsResolved) {
  PlanarContact contact;
  contact.setNormalForce([](int k) { return 1.0 / k; });
  EXPECT_FALSE(worstUnresolvedForce(contact.model, contact.full));
  EXPECT_EQ(unresolvedForceNote(contact.model, contact.full), "");
}

// A spectrum rising toward the truncation is named, with its bands.
TEST(ForceResolution, ARisingSpectrumIsNamedWithItsBands) {
  PlanarContact contact;
  contact.setNormalForce([](int k) { return k == 1 ? 1.8 : k > 30 ? 0.05 : k > 10 && k <= 20 ? 0.01 : 0.02; });
  const auto worst = worstUnresolvedForce(contact.model, contact.full);
  ASSERT_TRUE(worst);
  EXPECT_EQ(worst->law, 0);
  EXPECT_EQ(worst->component, 0);
  EXPECT_NEAR(worst->rise, 5.0, 1e-12);
  EXPECT_EQ(worst->top_from, 31);
  EXPECT_EQ(worst->top_to, 40);
  EXPECT_EQ(worst->middle_from, 11);
  EXPECT_EQ(worst->middle_to, 20);
  const std::string note = unresolvedForceNote(contact.model, contact.full);
  EXPECT_NE(note.find("law 1's force (law1.lambda1) is not resolved at H = 40 near omega = 0.126"), std::string::npos) << note;
  EXPECT_NE(note.find("harmonics 31-40 are 5 times its harmonics 11-20"), std::string::npos) << note;
}

// The same shape a million times below the fundamental is round-off, not a
// force the truncation misses.
TEST(ForceResolution, ANegligibleTopIsNotNamed) {
  PlanarContact contact;
  contact.setNormalForce([](int k) { return k == 1 ? 1e5 : k > 30 ? 0.05 : 0.01; });
  EXPECT_FALSE(worstUnresolvedForce(contact.model, contact.full));
}

// Too few harmonics for a trend, and coefficients of another size: no verdict.
TEST(ForceResolution, NoVerdictOnFewHarmonicsOrAnotherLayout) {
  PlanarContact few(6);
  few.setNormalForce([](int k) { return 0.01 * k; });
  EXPECT_FALSE(worstUnresolvedForce(few.model, few.full));
  PlanarContact contact;
  contact.setNormalForce([](int k) { return 0.01 * k; });
  ASSERT_TRUE(worstUnresolvedForce(contact.model, contact.full));
  EXPECT_FALSE(worstUnresolvedForce(contact.model, contact.full.head(contact.full.size() - 1)));
}

}  // namespace
}  // namespace eqhb
