// Sizes are refused, naming the field, before anything is allocated.
#include "eqhb/size_limits.h"

#include <gtest/gtest.h>

#include <chrono>
#include <climits>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/system_memory.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

using test::messageOf;

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

TEST(SizeLimits, AGeneratedStructureIsBoundedBeforeItIsBuilt) {
  // 2^24 DOFs x 20 coefficients: the coefficient vectors alone need 10 GiB,
  // while the chain's M, C and K (1.4 GB) pass their own bound. Refused from
  // the sizes, naming the key, instead of after building and factorising M.
  const auto start = std::chrono::steady_clock::now();
  const std::string chain = messageOf([] { loadScene(test::problem("friction-1d.toml"), {"structure.dofs=16777216"}); });
  EXPECT_NE(chain.find("structure.dofs = 16777216: the model (16777216 DOFs, 20 coefficients and 1024 samples"),
            std::string::npos)
      << chain;
  // A beam of 10^6 elements passes its matrices' bound (1.1 GB); with 80
  // coefficients its model does not.
  const std::string beam = messageOf([] {
    loadScene(test::problem("beam-damper.toml"), {"structure.elements=1000000", "harmonic_balance.harmonics=40"});
  });
  EXPECT_NE(beam.find("structure.elements = 1000000: the model (2000000 DOFs, 80 coefficients"), std::string::npos)
      << beam;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(SizeLimits, TheDensePathIsBoundedWhereTheSparsePathFits) {
  // A 20,000-DOF chain: dense A_k factors would need about 72 GiB; the
  // sparse factors and the full system's sparse Jacobian fit in a few MB.
  HbModel model = loadScene(test::problem("friction-1d.toml"), {"structure.dofs=20000"}).model;
  model.basis = HarmonicSet(HarmonicKind::kOdd, 3);
  model.samples = 64;
  EXPECT_GT(condensedBytes(model, false), kMaxModelBytes);
  EXPECT_LT(condensedBytes(model, true), 0.01 * kMaxModelBytes);
  EXPECT_LT(fullBytes(model), 0.1 * kMaxModelBytes);
  EXPECT_NE(messageOf([&] { makeHbSystem(model, true, LinearAlgebra::kDense); })
                .find("harmonics = 3: the condensed system with dense factors of A_k (20000 DOFs"),
            std::string::npos);
  const auto sparse = makeHbSystem(model, true, LinearAlgebra::kSparse);
  EXPECT_EQ(sparse->size(), 6);
}

TEST(SizeLimits, TheFullSystemIsRefusedWhereOnlyTheCondensedOneFits) {
  HbModel model = loadScene(test::problem("friction-1d.toml")).model;
  model.basis = HarmonicSet(HarmonicKind::kOdd, 4000);  // nb = 8000
  model.samples = 16384;
  // Condensed: 8000 dense unknowns; full: the law rows' 8000 x 8000 blocks
  // twice over in the sparse Jacobian and its copies.
  EXPECT_LT(condensedBytes(model, false), kMaxModelBytes);
  EXPECT_GT(fullBytes(model), kMaxModelBytes);
  EXPECT_NE(messageOf([&] { makeHbSystem(model, false); }).find("harmonics = 4000: the full system (2 DOFs"),
            std::string::npos);
  model.basis = HarmonicSet(HarmonicKind::kOdd, 40000);
  model.samples = 160001;
  EXPECT_NE(messageOf([&] { model.validate(); }).find("harmonics = 40000: the model"), std::string::npos);
}

}  // namespace
}  // namespace eqhb
