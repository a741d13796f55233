// Harmonic balance against the time reference (`eqhb compare`) on joint
// elements whose time step carries a slider under a varying normal load:
// elastic-friction in 2D and 3D (problems/elastic-friction-3d.toml) and
// contact-friction with an exact normal and k_t in 3D between two nodes
// (tests/scenes/contact-friction-3d.toml: not among the shipped problems,
// which the bare solver must solve from rest; `eqhb solve` reaches it by its
// coarse start). Each reference is checked to cross
// the phases the step must get right (open, stuck, slipping), so that an
// agreement is not that of a linear spring.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "eqhb/app/simulate.h"
#include "test_support.h"

namespace eqhb {
namespace {

// `eqhb compare SCENE --harmonics H --set ...` on the scene's time step.
app::Comparison compared(const std::string& path, int harmonics, const std::vector<std::string>& set = {},
                         const app::CompareOptions& options = {}) {
  app::SceneSettings scene;
  scene.path = path;
  scene.harmonics = harmonics;
  scene.overrides = set;
  app::Comparison c = app::compare(scene, options);
  EXPECT_TRUE(c.succeeded()) << path << " H = " << harmonics << ": " << c.hb.result.summary()
                             << (c.reference.periodic ? "" : "; the reference did not settle");
  return c;
}

// The largest relative L2 error of the displacements.
double displacementError(const app::Comparison& c) {
  double error = 0.0;
  for (const ChannelError& e : c.errors)
    if (e.label[0] == 'x') error = std::max(error, e.relative_l2);
  return error;
}

// Steps of the reference's last period by the friction's phase, from the
// law's pressure p (column 0 of the force, times `pressure_sign`, plus
// `preload`) and its tangential force on the columns after it.
struct Phases {
  int open = 0, stuck = 0, slipping = 0;
  double excess = 0.0;  // max (‖T‖ − μp) / μ max p: the disc is never left
};
Phases phases(const TimeReference& ref, double mu, double pressure_sign, double preload) {
  Phases out;
  const Eigen::MatrixXd& f = ref.force;
  const Eigen::VectorXd p = (preload + pressure_sign * f.col(0).array()).matrix();
  const double limit_scale = mu * p.maxCoeff();
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    const double t = f.row(i).tail(f.cols() - 1).norm(), limit = mu * std::max(p[i], 0.0);
    out.excess = std::max(out.excess, (t - limit) / limit_scale);
    if (p[i] <= 0.0) ++out.open;
    else if (t >= limit * (1.0 - 1e-9)) ++out.slipping;
    else if (t < 0.99 * limit) ++out.stuck;
  }
  return out;
}

void expectEveryPhase(const Phases& p, const std::string& what) {
  EXPECT_GT(p.open, 0) << what << ": the contact never opens";
  EXPECT_GT(p.stuck, 0) << what << ": the slider never sticks";
  EXPECT_GT(p.slipping, 0) << what << ": the slider never slips";
  EXPECT_LT(p.excess, 1e-9) << what << ": the tangential force leaves the disc of radius mu p";
}

// Elastic friction (λ = (p, T), no preload; μ = 0.5 in the scene): the
// displacement error at H = 5, 15, 30. It falls from H = 5 to 15; beyond,
// it stays at the reference's own error (first order in h across
// stick-slip and lift-off: halving h halves it), and at the 3D return map's
// on 512 samples (first order in their spacing).
std::vector<double> elasticFrictionErrors(const std::vector<std::string>& set, const std::string& what) {
  std::vector<double> errors;
  for (int h : {5, 15, 30}) {
    const app::Comparison c = compared(test::problem("elastic-friction-3d.toml"), h, set);
    expectEveryPhase(phases(c.reference, 0.5, 1.0, 0.0), what + " H = " + std::to_string(h));
    errors.push_back(displacementError(c));
  }
  return errors;
}

// Measured: 8.9e-3, 1.4e-3, 1.3e-3 (x L2, h = 2.5e-4, N = 512).
TEST(ElasticFrictionTimeReference, TwoDimensionalErrorFallsWithH) {
  const std::vector<double> e = elasticFrictionErrors({"law.dofs=[1,2]"}, "2D");
  EXPECT_LT(e[1], 0.3 * e[0]);
  EXPECT_LT(e[2], 1.1 * e[1]);
  EXPECT_LT(e[2], 2e-3);
}

// Measured: 4.1e-3, 2.0e-3, 2.0e-3 (x L2, h = 2.5e-4, N = 512).
TEST(ElasticFrictionTimeReference, ThreeDimensionalErrorFallsWithH) {
  const std::vector<double> e = elasticFrictionErrors({}, "3D");
  EXPECT_LT(e[1], 0.7 * e[0]);
  EXPECT_LT(e[2], 1.1 * e[1]);
  EXPECT_LT(e[2], 3e-3);
}

// contact-friction, form = "min" with k_t, between two nodes in 3D: λ_n =
// N0 − p (N0 = 1) and the friction force, μ = 0.4. Measured at H = 15
// (256 samples, h = 1e-3): x L2 8e-4 to 1.2e-2, the largest along the
// second tangent (x2, x5); the landings are impacts in the reference.
// The min form's harmonic balance has more than one root here, each to
// |g| < 1e-10: the dense LU dogleg's Broyden path from the coarse start
// lands on the one above; its refresh path (Newton steps while they are
// accepted, the default) on one 2.1e-2 off along x5, dogleg-newton on one
// 3.6e-2 off. The error bound is the one root's, so the path is fixed.
TEST(ContactFrictionTimeReference, ExactNormalWithElasticFrictionIn3DBetweenNodes) {
  app::CompareOptions broyden;
  broyden.hb.solver_options.backend = {{"update", "broyden"}};
  const app::Comparison c =
      compared(std::string(EQHB_TEST_SCENES_DIR) + "/contact-friction-3d.toml", 15, {}, broyden);
  expectEveryPhase(phases(c.reference, 0.4, -1.0, 1.0), "contact-friction 3D");
  EXPECT_LT(displacementError(c), 2e-2);
}

}  // namespace
}  // namespace eqhb
