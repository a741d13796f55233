// Hill's method on a large structure reduced to its law DOFs and the
// fixed-interface modes within the harmonics' band (stability/
// hill_reduction.h), on the blade with a tip damper (48 DOFs, one
// elastic-friction contact with two tangents, H = 5).
#include "eqhb/stability/hill_reduction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "eqhb/app/simulate.h"
#include "eqhb/app/solve.h"
#include "eqhb/stability/hill_stability.h"
#include "eqhb/stability/interface_reduction.h"
#include "test_support.h"

namespace eqhb {
namespace {

app::Solution bladeAt(double omega) {
  app::SceneSettings scene;
  scene.path = test::problem("blade-tip-damper.toml");
  scene.omega = omega;
  app::Solution s = app::solve(scene, app::SolveOptions());
  EXPECT_TRUE(s.converged()) << omega;
  return s;
}

HillResult hill(const app::Solution& s, int reduce_above) {
  HillOptions options;
  options.reduce_above = reduce_above;
  return hillStability(s.model(), s.full, options);
}

// Unreduced, the pencil carries the frame's axial and torsion modes (up to
// 4e6 rad/s against H ω = 3,000) and finds them unstable with spurious real
// parts (ω = 600: exponent 1.42e4 − 4.33e6 i, radius 3.8e64); the orbit is
// stable (the time-domain orbit started from the harmonic-balance one is
// periodic to 1e-9). Reduced, the verdict is stable and the exponents that
// the harmonics resolve are the unreduced pencil's (its spurious ones move
// with round-off: at ω = 770 they stayed below the physical ones, radius
// 0.989348 on both, until the pencil's rows were scaled; now 2.6e5).
TEST(HillReduction, BladeTipDamperKeepsTheResolvedExponentsOnly) {
  // The modes' exponents within the band in both (about −1.31 ± 656 i,
  // −8.2 ± 4113 i, −15.7 ± 7861 i at ω = 600).
  auto nearest = [](const HillResult& r, std::complex<double> s) {
    double d = 1e300;
    for (const FloquetExponent& e : r.exponents) d = std::min(d, std::abs(e.exponent - s));
    return d;
  };
  for (double omega : {600.0, 770.0}) {
    const app::Solution s = bladeAt(omega);
    const HillResult full = hill(s, 0), reduced = hill(s, HillOptions().reduce_above);
    ASSERT_TRUE(full.failure.empty()) << full.failure;
    ASSERT_TRUE(reduced.failure.empty()) << reduced.failure;
    if (omega == 600.0) {
      EXPECT_FALSE(full.stable);
      EXPECT_GT(full.spectral_radius, 1e10);
    }
    EXPECT_TRUE(reduced.stable) << omega;
    EXPECT_LT(reduced.spectral_radius, 1.0) << omega;
    EXPECT_LT(reduced.pencil_size, full.pencil_size / 4);
    EXPECT_LT(reduced.state_dimension, full.state_dimension);
    int compared = 0;
    for (const FloquetExponent& e : full.exponents) {
      // A structural mode's (its eigenvector on one harmonic) below the reduction's limit, 3 k_max ω.
      if (std::abs(e.exponent.imag()) > kResolvedBandMargin * 5 * omega || std::abs(e.centroid) > 0.05) continue;
      ++compared;
      EXPECT_LT(nearest(reduced, e.exponent), 0.05 * std::abs(e.exponent)) << omega << " " << e.exponent;
    }
    EXPECT_GE(compared, 6) << omega;
  }

  app::SimulateOptions time;
  time.from_hb = true;
  time.time.periods = 3000;
  app::SceneSettings scene;
  scene.path = test::problem("blade-tip-damper.toml");
  scene.omega = 600.0;
  const app::Simulation settles = app::simulate(scene, time);
  EXPECT_TRUE(settles.reference.periodic);
}

// A structure within the limit, or one whose modes are all within the band,
// is analysed as it is.
TEST(HillReduction, OnlyLargeStructuresAreReducedAndTheLawDofsKept) {
  const app::Solution s = bladeAt(770.0);
  EXPECT_FALSE(reduceForHill(s.model(), 200).has_value());
  EXPECT_FALSE(reduceForHill(s.model(), 0).has_value());
  const auto r = reduceForHill(s.model(), 20);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->model.structure.dofs(), 3 + r->modes_kept);  // the tip's three translations, then modes
  EXPECT_EQ(r->modes_kept + r->modes_dropped, 48 - 3);
  EXPECT_GT(r->modes_dropped, 30);
  // q = P x keeps the law DOFs as they are.
  const Eigen::VectorXd q = r->reduce(s.full);
  const int nb = s.model().basis.size();
  std::vector<int> law_dofs = s.model().laws[0].attachment.dofs();
  std::sort(law_dofs.begin(), law_dofs.end());
  ASSERT_EQ(law_dofs.size(), 3u);
  for (int j = 0; j < 3; ++j) {
    const Eigen::VectorXd x = s.full.segment(static_cast<Eigen::Index>(law_dofs[j]) * nb, nb);
    EXPECT_LE((q.segment(static_cast<Eigen::Index>(j) * nb, nb) - x).norm(), 1e-14 * x.norm()) << j;
  }
  EXPECT_EQ(q.size() - r->model.structure.dofs() * nb, s.full.size() - s.model().structure.dofs() * nb);
  // A solution of the wrong size is refused, naming it, before it is reduced.
  HillStability hill(s.model());
  const std::string message = test::messageOf([&] { hill.analyse(770.0, s.full.head(s.full.size() - 1)); });
  EXPECT_NE(message.find("solution"), std::string::npos) << message;
}

}  // namespace
}  // namespace eqhb
