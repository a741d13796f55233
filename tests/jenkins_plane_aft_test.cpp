// Jenkins on a plane in the AFT form (the `jenkins` law on 2 DOFs with
// formulation = "aft": elastic_friction_aft.h's tangential return map with a
// constant limit μN): driven along one axis it is the 1-D AFT Jenkins;
// turned in its plane it turns its force; on a circle it slides at its limit
// about the slider's circle of radius √(a² − (μN/k_t)²); a scene forced
// along one axis solves as the 1-D scene.
#include <gtest/gtest.h>

#include <cmath>

#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/laws/joints/elastic_friction_aft.h"
#include "eqhb/laws/joints/jenkins_aft.h"
#include "eqhb/scenes/scene.h"
#include "law_checks.h"
#include "test_support.h"

namespace eqhb {
namespace {

constexpr double kMuN = 1.2, kStiffness = 2.0;

std::shared_ptr<Law> planeLaw() {
  const Scene scene = parseScene(
      "name = \"plane\"\n[structure]\ntype = \"chain\"\ndofs = 2\nm = 1.0\nk = 1.0\nd = 0.05\n"
      "[[law]]\ntype = \"jenkins\"\ndofs = [1, 2]\nmuN = 1.2\nk_t = 2.0\nformulation = \"aft\"\n"
      "[harmonic_balance]\nharmonics = 3\nset = \"all\"\nsamples = 64\nomega = 0.8\n",
      "plane");
  return scene.model.laws.at(0).law;
}

LawSamples evaluated(const Law& law, const Eigen::MatrixXd& u) {
  LawSamples s;
  const int n = static_cast<int>(u.rows());
  s.resize(n, law.dimension(), law.historyTermsOn(n));
  s.displacement = u;
  law.evaluate(s, true);
  return s;
}

// u = a cos θ + 0.3 a sin 2θ along t1, b sin θ along t2, N samples.
Eigen::MatrixXd path(int n, double a, double b) {
  Eigen::MatrixXd u(n, 2);
  for (int i = 0; i < n; ++i) {
    const double theta = 2 * M_PI * i / n;
    u.row(i) << a * std::cos(theta) + 0.3 * a * std::sin(2 * theta), b * std::sin(theta);
  }
  return u;
}

TEST(JenkinsPlaneAft, TheSceneKeyBuildsTheReturnMapOnThePlane) {
  const auto law = planeLaw();
  const auto* plane = dynamic_cast<const ElasticFrictionAft*>(law.get());
  ASSERT_NE(plane, nullptr);
  EXPECT_TRUE(plane->onPlane());
  EXPECT_EQ(law->type(), "jenkins");
  EXPECT_EQ(law->dimension(), 2);
  EXPECT_EQ(law->forceSign(), 1.0);
  EXPECT_EQ(law->forceLevel(), kMuN);
}

TEST(JenkinsPlaneAft, DrivenAlongOneAxisIsTheOneDimensionalJenkins) {
  const auto plane = planeLaw();
  const JenkinsAft line({{kMuN, kStiffness}});
  // Slipping (amplitude 3) and stuck throughout (0.4).
  for (const double amplitude : {3.0, 0.4}) {
    const Eigen::MatrixXd u = path(96, amplitude, 0.0);
    const LawSamples a = evaluated(*plane, u), b = evaluated(line, u.col(0));
    EXPECT_LT((a.psi.col(0) - b.psi.col(0)).cwiseAbs().maxCoeff(), 1e-12) << amplitude;
    EXPECT_EQ(a.psi.col(1).cwiseAbs().maxCoeff(), 0.0) << amplitude;
    const Eigen::MatrixXd ja = test::sampleJacobian(*plane, a), jb = test::sampleJacobian(line, b);
    for (int i = 0; i < 96; ++i)
      for (int j = 0; j < 96; ++j) ASSERT_NEAR(ja(2 * i, 2 * j), jb(i, j), 1e-12) << amplitude << ": " << i << ", " << j;
  }
}

TEST(JenkinsPlaneAft, TurningThePathTurnsTheForce) {
  const auto plane = planeLaw();
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  const Eigen::MatrixXd u = path(128, 2.0, 1.3), turned = u * r.transpose();
  const LawSamples a = evaluated(*plane, u), b = evaluated(*plane, turned);
  const double scale = a.psi.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 0.5 * kMuN);
  EXPECT_LT((a.psi * r.transpose() - b.psi).cwiseAbs().maxCoeff(), 1e-10 * scale);
}

TEST(JenkinsPlaneAft, OnACircleItSlidesAtItsLimitAboutTheSlidersCircle) {
  // u = a (cos θ, sin θ), a = 3 > μN/k_t = 0.6: the force has the length μN
  // at every sample and the slider w = u + λ/k_t (λ = −T) runs on a circle;
  // in the continuum the force is along the slider's step (radial return)
  // and the step along the circle, so λ ⊥ w and |w|² = a² − (μN/k_t)². The
  // samples' map reaches that radius as the step 2π/N shrinks.
  const double a = 3.0, play = kMuN / kStiffness, radius = std::sqrt(a * a - play * play);
  const auto plane = planeLaw();
  auto radiusError = [&](int n) {
    Eigen::MatrixXd u(n, 2);
    for (int i = 0; i < n; ++i) u.row(i) << a * std::cos(2 * M_PI * i / n), a * std::sin(2 * M_PI * i / n);
    LawSamples s;
    s.resize(n, 2);
    s.displacement = u;
    plane->evaluate(s, false);
    const Eigen::MatrixXd lambda = -s.psi;  // Ψ = λ − F at λ = 0
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(lambda.row(i).norm(), kMuN, 1e-12) << n << ": " << i;
      const Eigen::RowVector2d w = u.row(i) + lambda.row(i) / kStiffness;
      worst = std::max(worst, std::abs(w.norm() - radius) / radius);
    }
    return worst;
  };
  const double coarse = radiusError(1024), fine = radiusError(4096);
  EXPECT_LT(fine, 2.0 / 4096);
  EXPECT_LT(fine, coarse / 3.0) << coarse;
}

TEST(JenkinsPlaneAft, JacobianAcrossSamplesMatchesFiniteDifferences) {
  const auto plane = planeLaw();
  for (unsigned seed : {3u, 11u}) test::expectHistoryPartialsMatch(*plane, "jenkins on a plane", seed, 24);
}

// A mass on two springs (x, y) held by Jenkins on the plane, forced along x
// only, moves along x as the mass on one spring held by the 1-D Jenkins.
TEST(JenkinsPlaneAft, ASceneForcedAlongOneAxisSolvesAsTheOneDimensionalScene) {
  const std::string tail =
      "[harmonic_balance]\nharmonics = 7\nset = \"all\"\nsamples = 256\nomega = 0.9\n";
  const Scene line = parseScene(
      "name = \"line\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0]]\nstiffness = [[1.0]]\ndamping = [[0.05]]\n"
      "[[law]]\ntype = \"jenkins\"\ndofs = [1]\nmuN = 0.6\nk_t = 2.0\nformulation = \"aft\"\n"
      "[[forcing]]\ndof = 1\ncos = 1.0\n" + tail,
      "line");
  const Scene plane = parseScene(
      "name = \"plane\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0, 0.0], [0.0, 1.0]]\n"
      "stiffness = [[1.0, 0.0], [0.0, 1.0]]\ndamping = [[0.05, 0.0], [0.0, 0.05]]\n"
      "[[law]]\ntype = \"jenkins\"\ndofs = [1, 2]\nmuN = 0.6\nk_t = 2.0\nformulation = \"aft\"\n"
      "[[forcing]]\ndof = 1\ncos = 1.0\n" + tail,
      "plane");
  const Eigen::VectorXd x_line = test::harmonicBalance(line.model);
  const Eigen::VectorXd x_plane = test::harmonicBalance(plane.model);
  const int nb = line.model.basis.size();
  ASSERT_GT(x_line.head(nb).norm(), 0.5);
  EXPECT_LT((x_plane.head(nb) - x_line.head(nb)).cwiseAbs().maxCoeff(), 1e-9 * x_line.head(nb).norm());
  EXPECT_LT(x_plane.segment(nb, nb).cwiseAbs().maxCoeff(), 1e-9 * x_line.head(nb).norm());
}

}  // namespace
}  // namespace eqhb
