#include "eqhb/harmonic_balance/fourier_transform.h"

#include <gtest/gtest.h>

#include <cmath>

#include "eqhb/error.h"

namespace eqhb {
namespace {

Eigen::MatrixXd basisSamples(const HarmonicSet& basis, int n) {
  Eigen::MatrixXd p(n, basis.size());
  for (int i = 0; i < n; ++i) {
    const double theta = 2 * M_PI * i / n;
    for (size_t h = 0; h < basis.harmonics().size(); ++h) {
      const int k = basis.harmonics()[h], o = basis.offset(static_cast<int>(h));
      if (k == 0) {
        p(i, o) = 1.0;
      } else {
        p(i, o) = std::cos(k * theta);
        p(i, o + 1) = std::sin(k * theta);
      }
    }
  }
  return p;
}

class TransformTest : public ::testing::TestWithParam<std::tuple<HarmonicKind, int, int>> {};

TEST_P(TransformTest, SynthesisMatchesTheSeriesAndProjectionInvertsIt) {
  const auto [kind, count, n] = GetParam();
  HarmonicSet basis(kind, count);
  FourierTransform transform(basis, n);
  const Eigen::VectorXd c = Eigen::VectorXd::Random(basis.size());
  Eigen::VectorXd samples(n), back(basis.size());
  transform.synthesize(c.data(), samples.data());
  EXPECT_LT((samples - basisSamples(basis, n) * c).norm(), 1e-12 * n);
  transform.project(samples.data(), back.data());
  EXPECT_LT((back - c).norm(), 1e-13 * basis.size());
}

TEST_P(TransformTest, GramEqualsTheDenseWeightedProduct) {
  const auto [kind, count, n] = GetParam();
  HarmonicSet basis(kind, count);
  FourierTransform transform(basis, n);
  const Eigen::VectorXd d = Eigen::VectorXd::Random(n);
  const Eigen::MatrixXd p = basisSamples(basis, n);
  Eigen::MatrixXd q = p.transpose() * (2.0 / n);
  if (basis.harmonics().front() == 0) q.row(0) *= 0.5;
  const Eigen::MatrixXd dense = q * d.asDiagonal() * p;
  Eigen::MatrixXd fast(basis.size(), basis.size());
  transform.gram(d.data(), fast);
  EXPECT_LT((fast - dense).cwiseAbs().maxCoeff(), 1e-13);
}

TEST_P(TransformTest, DerivativeMatchesTimeDifferences) {
  const auto [kind, count, n] = GetParam();
  HarmonicSet basis(kind, count);
  FourierTransform transform(basis, n);
  const double omega = 0.7;
  const Eigen::VectorXd c = Eigen::VectorXd::Random(basis.size());
  Eigen::VectorXd dc(basis.size()), rate(n);
  transform.differentiate(c.data(), omega, dc.data());
  transform.synthesize(dc.data(), rate.data());
  // d/dt at t_3 by central differences of the series itself.
  const double t = 3 * (2 * M_PI / omega) / n, h = 1e-6;
  auto value = [&](double time) {
    double v = 0.0;
    for (size_t k = 0; k < basis.harmonics().size(); ++k) {
      const int m = basis.harmonics()[k], o = basis.offset(static_cast<int>(k));
      v += m == 0 ? c[o] : c[o] * std::cos(m * omega * time) + c[o + 1] * std::sin(m * omega * time);
    }
    return v;
  };
  EXPECT_NEAR(rate[3], (value(t + h) - value(t - h)) / (2 * h), 1e-5 * (1 + std::abs(rate[3])));
}

INSTANTIATE_TEST_SUITE_P(Bases, TransformTest,
                         ::testing::Values(std::make_tuple(HarmonicKind::kOdd, 10, 1024),
                                           std::make_tuple(HarmonicKind::kOdd, 10, 39),
                                           std::make_tuple(HarmonicKind::kAll, 7, 15),
                                           std::make_tuple(HarmonicKind::kAll, 12, 64),
                                           std::make_tuple(HarmonicKind::kOdd, 40, 512)));

TEST(FourierTransform, RejectsTooFewSamples) {
  HarmonicSet basis(HarmonicKind::kOdd, 10);  // highest harmonic 19 needs N >= 39
  EXPECT_THROW(FourierTransform(basis, 38), InputError);
  EXPECT_NO_THROW(FourierTransform(basis, 39));
}

TEST(HarmonicSet, OddSetOfTenHarmonicsIsOneToNineteen) {
  HarmonicSet odd(HarmonicKind::kOdd, 10);
  EXPECT_EQ(odd.harmonics().front(), 1);
  EXPECT_EQ(odd.harmonics().back(), 19);
  EXPECT_EQ(odd.size(), 20);
  HarmonicSet all(HarmonicKind::kAll, 3);
  EXPECT_EQ(all.size(), 7);
  EXPECT_THROW(HarmonicSet(HarmonicKind::kOdd, 0), InputError);
}

// Half-wave sampling against the full period: the first N/2 samples of the
// synthesis, the projection of an antiperiodic signal from its first half,
// and the Gram block of half-period periodic weights, each to rounding; and
// the fallback to the full period where it does not apply.
TEST(HalfWaveTransform, AgreesWithTheFullPeriod) {
  for (int count : {1, 3, 10}) {
    for (int n : {64, 1024, 130, 134}) {  // 134: M = 67 is prime, no pruning
      HarmonicSet basis(HarmonicKind::kOdd, count);
      FourierTransform full(basis, n), half(basis, n, Sampling::kHalfWave);
      ASSERT_TRUE(half.halfWave());
      ASSERT_EQ(half.activeSamples(), n / 2);
      const Eigen::VectorXd c = Eigen::VectorXd::Random(basis.size());
      Eigen::VectorXd xf(n), xh(n / 2), cf(basis.size()), ch(basis.size());
      full.synthesize(c.data(), xf.data());
      half.synthesize(c.data(), xh.data());
      EXPECT_LT((xh - xf.head(n / 2)).cwiseAbs().maxCoeff(), 1e-13 * basis.size()) << count << " " << n;
      // an odd function of an antiperiodic signal is antiperiodic
      const Eigen::VectorXd y = xf.array().cube() + xf.array().sin();
      full.project(y.data(), cf.data());
      half.project(y.data(), ch.data());
      EXPECT_LT((ch - cf).cwiseAbs().maxCoeff(), 1e-13 * (1 + cf.cwiseAbs().maxCoeff())) << count << " " << n;
      half.project(xh.data(), ch.data());
      EXPECT_LT((ch - c).cwiseAbs().maxCoeff(), 1e-13 * basis.size());
      // an even function of it has period T/2
      const Eigen::VectorXd w = xf.array().square() + xf.array().cos();
      Eigen::MatrixXd gf(basis.size(), basis.size()), gh(basis.size(), basis.size());
      full.gram(w.data(), gf);
      half.gram(w.data(), gh);
      EXPECT_LT((gh - gf).cwiseAbs().maxCoeff(), 1e-13 * (1 + gf.cwiseAbs().maxCoeff())) << count << " " << n;
    }
  }
  FourierTransform all(HarmonicSet(HarmonicKind::kAll, 4), 64, Sampling::kHalfWave);
  EXPECT_FALSE(all.halfWave());
  EXPECT_EQ(all.activeSamples(), 64);
  FourierTransform odd_n(HarmonicSet(HarmonicKind::kOdd, 4), 65, Sampling::kHalfWave);
  EXPECT_FALSE(odd_n.halfWave());
}

// Two channels synthesised by one transform (real and imaginary parts)
// equal two separate syntheses, with and without half-wave sampling.
TEST(HalfWaveTransform, PairEqualsTwoSyntheses) {
  for (int count : {1, 3, 10}) {
    for (int n : {64, 1024, 130, 134}) {
      for (Sampling sampling : {Sampling::kHalfWave, Sampling::kFullPeriod}) {
        HarmonicSet basis(HarmonicKind::kOdd, count);
        FourierTransform transform(basis, n, sampling);
        const int m = transform.activeSamples();
        const Eigen::VectorXd c1 = Eigen::VectorXd::Random(basis.size()), c2 = Eigen::VectorXd::Random(basis.size());
        Eigen::VectorXd x1(m), x2(m), y1(m), y2(m);
        transform.synthesize(c1.data(), x1.data());
        transform.synthesize(c2.data(), x2.data());
        transform.synthesizePair(c1.data(), c2.data(), y1.data(), y2.data());
        EXPECT_LT((y1 - x1).cwiseAbs().maxCoeff(), 1e-13 * basis.size()) << count << " " << n;
        EXPECT_LT((y2 - x2).cwiseAbs().maxCoeff(), 1e-13 * basis.size()) << count << " " << n;
        EXPECT_GT(x2.cwiseAbs().maxCoeff(), 0.1);  // the channels are not trivially zero
      }
    }
  }
}

// Channels of very different sizes (a velocity of 1e-9 m/s beside a force of
// 1 N): each keeps its own relative precision, and a power-of-two change of
// the second channel's unit changes none of its bits (a change of time unit
// must not change a solve).
TEST(HalfWaveTransform, PairKeepsTheSmallerChannelsPrecision) {
  HarmonicSet basis(HarmonicKind::kOdd, 10);
  FourierTransform transform(basis, 128, Sampling::kHalfWave);
  ASSERT_TRUE(transform.halfWave());
  const int m = transform.activeSamples();
  const Eigen::VectorXd large = Eigen::VectorXd::Random(basis.size());
  const Eigen::VectorXd small = 1e-9 * Eigen::VectorXd::Random(basis.size());
  Eigen::VectorXd alone(m), y1(m), y2(m), scaled1(m), scaled2(m);
  transform.synthesize(small.data(), alone.data());
  transform.synthesizePair(large.data(), small.data(), y1.data(), y2.data());
  EXPECT_LT((y2 - alone).cwiseAbs().maxCoeff(), 1e-13 * basis.size() * alone.cwiseAbs().maxCoeff());
  const Eigen::VectorXd small_in_other_unit = small / 128.0;
  transform.synthesizePair(large.data(), small_in_other_unit.data(), scaled1.data(), scaled2.data());
  EXPECT_EQ(scaled1, y1);
  EXPECT_EQ(scaled2 * 128.0, y2);
}

}  // namespace
}  // namespace eqhb
