// Sizes are refused, naming the field, before anything is allocated.
#include "eqhb/size_limits.h"

#include <gtest/gtest.h>

#include <climits>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SizeLimits, HarmonicCountIsBoundedBeforeKmaxOverflows) {
  // 2 H − 1 overflows int at H = INT_MAX.
  EXPECT_NE(messageOf([] { HarmonicSet(HarmonicKind::kOdd, INT_MAX); }).find("harmonics = 2147483647: must be <="),
            std::string::npos);
  EXPECT_NE(messageOf([] { HarmonicSet(HarmonicKind::kAll, kMaxHarmonics + 1); }).find("must be <="),
            std::string::npos);
  EXPECT_EQ(HarmonicSet(HarmonicKind::kOdd, 1000).highest(), 1999);
}

TEST(SizeLimits, SampleCountIsBoundedBeforeFftwPlans) {
  const HarmonicSet basis(HarmonicKind::kOdd, 3);
  EXPECT_NE(messageOf([&] { FourierTransform(basis, kMaxSamples + 1); }).find("samples = 16777217: must be <="),
            std::string::npos);
}

}  // namespace
}  // namespace eqhb
