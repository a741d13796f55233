// Model validation beyond the scene file: rules that tie the laws to the
// harmonic basis.
#include <gtest/gtest.h>

#include <memory>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

std::string validationMessage(const HbModel& model) {
  try {
    model.validate();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A contact pressure p >= 0 has a positive mean whenever it is not zero: an
// odd-only basis would meet the law only by letting the wall pull.
TEST(HbModel, ContactNeedsTheConstantTerm) {
  for (const auto form : {SignoriniForm::kMin, SignoriniForm::kFischerBurmeister, SignoriniForm::kSignSquare}) {
    HbModel model = test::chainWithFriction(7.2, CoulombForm::kMinMax, 10, 0.5, 256, HarmonicKind::kOdd);
    model.laws.push_back({{0}, std::make_shared<Signorini>(2.0, form)});
    const std::string message = validationMessage(model);
    EXPECT_NE(message.find("harmonic_balance.set = \"odd\""), std::string::npos) << message;
    EXPECT_NE(message.find("law[1] (signorini) needs the constant term"), std::string::npos) << message;
    model.basis = HarmonicSet(HarmonicKind::kAll, 10);
    EXPECT_EQ(validationMessage(model), "");
  }
}

TEST(HbModel, FrictionAloneSolvesOnOddHarmonics) {
  EXPECT_EQ(validationMessage(test::chainWithFriction(7.2, CoulombForm::kMinMax, 10, 0.4)), "");
}

TEST(HbModel, TheContactSceneOnOddHarmonicsIsRejectedNamingTheField) {
  try {
    loadScene(test::problem("contact.toml"), {"harmonic_balance.set=odd"});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("contact.toml: harmonic_balance.set = \"odd\""), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace eqhb
