// The Iwan element (laws/joints/iwan_sliders.h) in the alternating
// frequency–time form: its sliders keep the joint's stiffness and slip
// force, its hysteresis loop under a sine dissipates what its sliders do
// (4 f (a − φ) each), the micro-slip dissipation follows the four-parameter
// model's power law, and harmonic balance with it converges, reducing to the
// Jenkins element for one slider.
#include <gtest/gtest.h>

#include <cmath>

#include "eqhb/error.h"
#include "eqhb/laws/joints/iwan_sliders.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/scenes/scene.h"
#include "law_checks.h"
#include "test_support.h"

namespace eqhb {
namespace {

IwanParameters parameters(double chi, double beta, int cells) {
  IwanParameters p;
  p.slip_force = 1.2;
  p.stiffness = 2.0;
  p.chi = chi;
  p.beta = beta;
  p.cells = cells;
  return p;
}

TEST(Iwan, SlidersKeepStiffnessAndSlipForce) {
  for (double chi : {-0.8, -0.5, 0.0, 0.5})
    for (double beta : {0.0, 0.1, 2.0}) {
      const IwanParameters p = parameters(chi, beta, 10);
      const auto sliders = iwanSliders(p);
      ASSERT_EQ(sliders.size(), beta > 0.0 ? 11u : 10u);
      double k = 0.0, f = 0.0, largest = 0.0;
      for (const auto& s : sliders) {
        EXPECT_GT(s.k_t, 0.0);
        k += s.k_t;
        f += s.mu_n;
        largest = std::max(largest, s.mu_n / s.k_t);
      }
      EXPECT_NEAR(k, 2.0, 1e-13) << chi << " " << beta;
      EXPECT_NEAR(f, 1.2, 1e-13) << chi << " " << beta;
      // The concentrated part slips at φ_max; the last cell's centroid lies
      // within that cell.
      const double phi_max = iwanMaxSlipDisplacement(p);
      if (beta > 0.0) EXPECT_NEAR(largest, phi_max, 1e-13 * phi_max);
      else EXPECT_TRUE(largest > 0.9 * phi_max && largest < phi_max) << largest << " " << phi_max;
    }
  // χ = 0, β = 0: equal stiffnesses, slip displacements at the cells'
  // midpoints of (0, 2 F_S / K_T).
  const auto uniform = iwanSliders(parameters(0.0, 0.0, 10));
  for (int j = 0; j < 10; ++j) {
    EXPECT_NEAR(uniform[j].k_t, 0.2, 1e-15);
    EXPECT_NEAR(uniform[j].mu_n / uniform[j].k_t, (j + 0.5) * 1.2 / 10, 1e-14);
  }
  EXPECT_THROW(iwanSliders(parameters(-1.0, 0.0, 10)), InputError);
  EXPECT_THROW(iwanSliders(parameters(0.0, -0.1, 10)), InputError);
  EXPECT_THROW(iwanSliders(parameters(0.0, 0.0, 0)), InputError);
}

// The energy the element dissipates over one period of x = a sin θ, −∮ F dx,
// from the law's force on n samples (F = −Ψ at λ = 0).
double loopDissipation(const Law& law, double a, int n) {
  LawSamples s;
  s.resize(n, 1, law.historyTerms());
  for (int i = 0; i < n; ++i) s.displacement(i, 0) = a * std::sin(2 * M_PI * i / n);
  law.evaluate(s, false);
  double work = 0.0;
  for (int i = 0; i < n; ++i) work += -s.psi(i, 0) * a * std::cos(2 * M_PI * i / n) * 2 * M_PI / n;
  return -work;
}

TEST(Iwan, LoopDissipatesWhatItsSlidersDo) {
  const IwanParameters p = parameters(-0.5, 0.5, 12);
  const auto sliders = iwanSliders(p);
  const JenkinsAft law(sliders, "iwan");
  const double phi_max = iwanMaxSlipDisplacement(p);
  for (double fraction : {0.3, 0.8, 1.5}) {
    const double a = fraction * phi_max;
    // A slider of slip displacement φ < a slips over 2(a − φ) twice a
    // period at force f: 4 f (a − φ).
    double expected = 0.0;
    for (const auto& s : sliders) expected += 4.0 * s.mu_n * std::max(0.0, a - s.mu_n / s.k_t);
    EXPECT_NEAR(loopDissipation(law, a, 8192), expected, 1e-5 * expected) << fraction;
  }
}

// Segalman's continuum: D(a) = 4 R a^{χ+3} / ((χ+2)(χ+3)) for a <= φ_max,
// approached by a fine discretisation.
TEST(Iwan, MicroSlipDissipationFollowsThePowerLaw) {
  for (double chi : {-0.5, 0.0}) {
    const IwanParameters p = parameters(chi, 0.5, 400);
    const JenkinsAft law(iwanSliders(p), "iwan");
    const double phi_max = iwanMaxSlipDisplacement(p);
    const double r = p.slip_force * (chi + 1) / (std::pow(phi_max, chi + 2) * (p.beta + (chi + 1) / (chi + 2)));
    for (double fraction : {0.25, 0.5, 0.9}) {
      const double a = fraction * phi_max;
      const double continuum = 4 * r * std::pow(a, chi + 3) / ((chi + 2) * (chi + 3));
      EXPECT_NEAR(loopDissipation(law, a, 8192), continuum, 2e-3 * continuum) << chi << " " << fraction;
    }
  }
}

// jenkins-1d (μN = 7.2, k_t = 5) with its slider replaced by an Iwan element
// of the same slip force and stiffness, solved from rest.
struct IwanSolve {
  SolverResult result;
  Eigen::VectorXd full;
};
IwanSolve solveWithIwan(const IwanParameters* p) {
  HbModel model = loadScene(test::problem("jenkins-1d.toml"), {"law.formulation=\"aft\""}).model;
  const auto& jenkins = dynamic_cast<const JenkinsAft&>(*model.laws[0].law);
  EXPECT_EQ(jenkins.sliders().front().mu_n, 7.2);
  EXPECT_EQ(jenkins.sliders().front().k_t, 5.0);
  if (p) model.laws[0].law = std::make_shared<JenkinsAft>(iwanSliders(*p), "iwan");
  const auto system = makeHbSystem(model, true);
  IwanSolve s;
  s.result = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
  s.full = system->fullCoefficients(s.result.solution);
  return s;
}

TEST(Iwan, HarmonicBalanceConvergesAndOneSliderIsJenkins) {
  IwanParameters p;
  p.slip_force = 7.2;
  p.stiffness = 5.0;
  p.cells = 1;
  const IwanSolve reference = solveWithIwan(nullptr), one = solveWithIwan(&p);
  ASSERT_TRUE(one.result.converged() && reference.result.converged());
  EXPECT_LT((one.full - reference.full).cwiseAbs().maxCoeff(), 1e-9 * reference.full.cwiseAbs().maxCoeff());
  p.cells = 20;
  p.chi = -0.5;
  p.beta = 0.5;
  const IwanSolve iwan = solveWithIwan(&p);
  ASSERT_TRUE(iwan.result.converged()) << iwan.result.summary();
  // Micro-slip softens and damps before the joint slips as a whole: the
  // response differs from the single slider's.
  EXPECT_GT((iwan.full - reference.full).cwiseAbs().maxCoeff(), 1e-3 * reference.full.cwiseAbs().maxCoeff());
}

TEST(Iwan, SceneErrorsNameTheField) {
  const LawEntry& entry = *findLaw("iwan");
  const std::string text = test::exampleScene(entry, entry.examples.front());
  auto message = [&](const std::string& set) {
    try {
      parseScene(text, "scene", {set});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("law[0].sliders=10"), "");
  EXPECT_NE(message("law[0].sliders=2.5").find("law[0].sliders = 2.5: must be an integer"), std::string::npos);
  EXPECT_NE(message("law[0].chi=-1").find("law[0].chi = -1"), std::string::npos);
  const std::string equality = message("law[0].formulation=\"equality\"");
  EXPECT_NE(equality.find("law[0].formulation = \"equality\": a iwan law has no equality form"), std::string::npos)
      << equality;
}

}  // namespace
}  // namespace eqhb
