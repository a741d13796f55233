// The smooth elements besides the cubic spring: a polynomial spring and a
// quadratic damper (laws/polynomial_stiffness.h, laws/quadratic_damping.h),
// against closed forms and the time reference.
#include <gtest/gtest.h>

#include <cmath>

#include "eqhb/orbits/shooting.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/references/time_integrator.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

// A 1-DOF oscillator (m = k = 1, viscous damping d) forced by f cos ωt with
// one law given by its TOML lines.
std::string oscillator(const std::string& law, double d, double f, double omega, int harmonics,
                       const std::string& set, int samples) {
  return "name = \"oscillator\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0]]\ndamping = [[" +
         std::to_string(d) + "]]\nstiffness = [[1.0]]\n[[forcing]]\ndof = 1\nharmonic = 1\ncos = " +
         std::to_string(f) + "\n[[law]]\n" + law + "\ndofs = [1]\n[harmonic_balance]\nharmonics = " +
         std::to_string(harmonics) + "\nset = \"" + set + "\"\nsamples = " + std::to_string(samples) +
         "\nomega = " + std::to_string(omega) + "\n";
}

// The time reference (the law's own step, not its harmonic-balance
// evaluation) from the harmonic-balance start reaches a periodic state whose
// every channel is within 0.2 % (L2) of harmonic balance.
void expectTheTimeReferenceAgrees(const HbModel& model, const Eigen::VectorXd& hb) {
  TimeOptions options;
  options.step = 1e-3;
  options.periodic_tolerance = 1e-9;
  const TimeReference ref = integrateToSteadyState(model, options, hb);
  ASSERT_TRUE(ref.periodic);
  for (const ChannelError& e : compareWithReference(model, hb, ref)) EXPECT_LT(e.relative_l2, 2e-3) << e.label;
}

// x³ as a polynomial is the cubic spring, to rounding.
TEST(PolynomialStiffness, ItsCubicTermIsTheCubicSpring) {
  const HbModel cubic = parseScene(oscillator("type = \"cubic\"\nepsilon = 0.1", 0.05, 0.18, 1.2, 7, "all", 32), "c").model;
  const HbModel poly = parseScene(
      oscillator("type = \"polynomial\"\ncoefficients = [0.1]\nexponents = [3]", 0.05, 0.18, 1.2, 7, "all", 32), "p").model;
  const Eigen::VectorXd a = test::harmonicBalance(cubic), b = test::harmonicBalance(poly);
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12 * a.cwiseAbs().maxCoeff());
}

// An even power pulls one way: the response gets a mean, and harmonic
// balance on 0..9 agrees with the time reference.
TEST(PolynomialStiffness, AQuadraticTermShiftsTheMeanAsTheTimeReferenceDoes) {
  const HbModel model = parseScene(
      oscillator("type = \"polynomial\"\ncoefficients = [0.3, 0.1]\nexponents = [2, 3]", 0.1, 0.3, 0.8, 9, "all", 64),
      "q").model;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  // x's constant term: a mean pulled towards −x by the force −0.3 x².
  EXPECT_LT(hb[0], -1e-3);
  expectTheTimeReferenceAgrees(model, hb);
}

// At ω = √(k/m) the spring and the mass cancel and the dampers alone hold
// the force: on the fundamental alone, f = d ω X + (8/(3π)) c ω² X² (the
// describing function), a quadratic in X (quadrature error below 1e-9).
TEST(QuadraticDamping, AtResonanceTheFundamentalIsTheDescribingFunctions) {
  const double c = 0.4, d = 0.01, f = 0.05;
  const HbModel model =
      parseScene(oscillator("type = \"quadratic-damping\"\ncoefficient = 0.4", d, f, 1.0, 1, "odd", 1024), "d").model;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  const double amplitude = std::hypot(hb[0], hb[1]), a = 8.0 * c / (3.0 * M_PI);
  EXPECT_NEAR(amplitude, (-d + std::sqrt(d * d + 4.0 * a * f)) / (2.0 * a), 1e-9);
}

// On 15 odd harmonics the damper's response is the time reference's.
TEST(QuadraticDamping, HarmonicBalanceAgreesWithTheTimeReference) {
  const HbModel model = parseScene(
      oscillator("type = \"quadratic-damping\"\ncoefficient = 0.4", 0.02, 0.2, 0.9, 15, "odd", 128), "d").model;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  expectTheTimeReferenceAgrees(model, hb);
}

// The exact periodic orbit (smooth flow, shooting) of both elements
// together, with an even power: harmonic balance on 0..15 reaches max|x| to
// 1e-6 and shooting converges from it in few Newton steps.
TEST(SmoothElements, ExactOrbitsAgreeWithHarmonicBalance) {
  const HbModel model =
      parseScene("name = \"both\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0]]\ndamping = [[0.02]]\n"
                 "stiffness = [[1.0]]\n[[forcing]]\ndof = 1\nharmonic = 1\ncos = 0.2\n"
                 "[[law]]\ntype = \"quadratic-damping\"\ncoefficient = 0.4\ndofs = [1]\n"
                 "[[law]]\ntype = \"polynomial\"\ncoefficients = [0.2, 0.1]\nexponents = [2, 3]\ndofs = [1]\n"
                 "[harmonic_balance]\nharmonics = 15\nset = \"all\"\nsamples = 128\nomega = 0.9\n",
                 "both")
          .model;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  const auto flow = orbits::makeFlow(model, 0.0);
  const orbits::ShootingResult orbit = orbits::shootFromHarmonicBalance(*flow, model, hb, {});
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  EXPECT_LE(orbit.iterations, 3);
  double hb_max = 0.0;
  for (int k = 0; k < 4096; ++k) {
    const double t = 2.0 * M_PI / model.omega * k / 4096.0;
    hb_max = std::max(hb_max, std::abs(orbits::harmonicState(model, hb, t)[0]));
  }
  EXPECT_NEAR(hb_max / orbit.max_abs[0], 1.0, 1e-6);
  EXPECT_TRUE(orbit.stable);
}

}  // namespace
}  // namespace eqhb
