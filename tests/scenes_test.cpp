// The shipped scenes, solved at their defaults (and with more harmonics):
// physical invariants of the converged solutions sampled densely in time
// (8x the scene's N). The tolerances are the Fourier-truncation errors: a
// finite series cannot jump where the force or velocity does, so the
// violations shrink with H instead of vanishing.
#include <gtest/gtest.h>

#include <map>

#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/invariants.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/backends/registry.h"
#include "test_support.h"

namespace eqhb {
namespace {

struct Solved : test::SolvedScene {
  std::map<std::string, double> violations;  // of law 0
};

Solved solveScene(const std::string& file, bool condensed, std::vector<std::string> set = {},
                  const std::string& solver = "dogleg") {
  Solved s;
  static_cast<test::SolvedScene&>(s) = test::solveFromRest(file, set, condensed, solver);
  const auto reports = checkInvariants(s.model, s.full);
  for (const auto& [name, value] : reports[0].violations) s.violations[name] = value;
  return s;
}

TEST(Scenes, Friction1dSaturatesAndOpposesSliding) {
  const Solved h10 = solveScene("friction-1d.toml", true);
  const Solved h40 = solveScene("friction-1d.toml", true, {"harmonic_balance.harmonics=40"});
  ASSERT_TRUE(h10.result.converged() && h40.result.converged());
  EXPECT_LT(h40.violations.at("force_limit_excess"), 0.07);
  EXPECT_LT(h40.violations.at("sliding_force_error"), 0.07);
  EXPECT_LT(h40.violations.at("force_limit_excess"), h10.violations.at("force_limit_excess"));
  EXPECT_LT(h40.violations.at("sliding_force_error"), h10.violations.at("sliding_force_error"));
}

TEST(Scenes, Friction2dStickSlipRespectsTheFrictionDisc) {
  for (bool condensed : {true, false}) {
    const Solved s = solveScene("friction-2d.toml", condensed);
    ASSERT_TRUE(s.result.converged()) << s.result.summary();
    EXPECT_LT(s.violations.at("force_limit_excess"), 0.05);
    EXPECT_LT(s.violations.at("sliding_force_error"), 0.25);
  }
  const Solved fine = solveScene("friction-2d.toml", true, {"harmonic_balance.harmonics=80"});
  ASSERT_TRUE(fine.result.converged()) << fine.result.summary();
  EXPECT_LT(fine.violations.at("force_limit_excess"), 0.03);
  EXPECT_LT(fine.violations.at("sliding_force_error"), 0.04);
  // Stick-slip: the speed drops to (near) zero in part of the period.
  FourierTransform transform(fine.model.basis, 8 * fine.model.samples);
  const int nb = fine.model.basis.size();
  Eigen::VectorXd vx(nb), vy(nb), sx(transform.samples()), sy(transform.samples());
  transform.differentiate(fine.full.data(), fine.model.omega, vx.data());
  transform.differentiate(fine.full.data() + nb, fine.model.omega, vy.data());
  transform.synthesize(vx.data(), sx.data());
  transform.synthesize(vy.data(), sy.data());
  const Eigen::ArrayXd speed = (sx.array().square() + sy.array().square()).sqrt();
  EXPECT_LT(speed.minCoeff(), 0.02 * speed.maxCoeff());
}

TEST(Scenes, Friction2dPureSlidingIsSmoothAndExact) {
  const Solved s = solveScene("friction-2d-sliding.toml", true, {"harmonic_balance.harmonics=40"});
  ASSERT_TRUE(s.result.converged()) << s.result.summary();
  // Never sticking, the friction force is smooth: ‖r‖ = μN pointwise.
  EXPECT_LT(s.violations.at("force_limit_excess"), 1e-4);
  EXPECT_LT(s.violations.at("sliding_force_error"), 1e-4);
}

TEST(Scenes, ContactNeitherPenetratesNorPulls) {
  const Solved s = solveScene("contact.toml", false);
  ASSERT_TRUE(s.result.converged()) << s.result.summary();
  EXPECT_LT(s.violations.at("penetration"), 0.05);
  EXPECT_LT(s.violations.at("negative_pressure"), 0.1);
  EXPECT_LT(s.violations.at("complementarity"), 0.02);
  // Contact is active over part of the period: a pressure peak, and a gap.
  const HbModel& m = s.model;
  const int nb = m.basis.size();
  EXPECT_GT(s.full.segment(2 * nb, nb)[0], 0.0);  // positive mean pressure
}

TEST(Scenes, StribeckSolutionFollowsTheVelocityWeakeningLimit) {
  const Solved h10 = solveScene("stribeck.toml", true);
  const Solved h40 = solveScene("stribeck.toml", true, {"harmonic_balance.harmonics=40"});
  ASSERT_TRUE(h10.result.converged() && h40.result.converged());
  EXPECT_LT(h40.violations.at("force_limit_excess"), 0.15);
  EXPECT_LT(h40.violations.at("sliding_force_error"), 0.15);
  EXPECT_LT(h40.violations.at("sliding_force_error"), h10.violations.at("sliding_force_error"));
}

// The classical explicit harmonic balance of the cubic chain: unknowns x
// only, the force −ε x2³ computed in time and projected (AFT).
class ExplicitCubic : public SquareSystem {
 public:
  explicit ExplicitCubic(const HbModel& model, double epsilon)
      : model_(model), epsilon_(epsilon), transform_(model.basis, model.samples),
        nb_(model.basis.size()), x2_(model.samples), f_(model.samples), coeffs_(nb_) {
    FullSystem full(model);  // reuse the exact linear blocks: z = [x; f_nl]
    Eigen::VectorXd g(full.size());
    const int n = full.size() - nb_;
    linear_.resize(n, n);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(full.size());
    full.residual(z, g);
    forcing_ = -g.head(n);
    for (int c = 0; c < n; ++c) {
      z.setZero();
      z[c] = 1.0;
      full.residual(z, g);
      linear_.col(c) = g.head(n) + forcing_;
    }
  }
  int size() const override { return 2 * nb_; }
  Eigen::VectorXd linearResponse() const { return linear_.lu().solve(forcing_); }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> g) override {
    g = linear_ * x - forcing_;
    transform_.synthesize(x.data() + nb_, x2_.data());
    for (int i = 0; i < model_.samples; ++i) f_[i] = -epsilon_ * x2_[i] * x2_[i] * x2_[i];
    transform_.project(f_.data(), coeffs_.data());
    g.tail(nb_) -= coeffs_;
    return true;
  }
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> j) override {
    residual(x, g);
    j = linear_;
    for (int i = 0; i < model_.samples; ++i) f_[i] = 3.0 * epsilon_ * x2_[i] * x2_[i];
    Eigen::MatrixXd block(nb_, nb_);
    transform_.gram(f_.data(), block);
    j.block(nb_, nb_, nb_, nb_) += block;
    return true;
  }

 private:
  HbModel model_;
  double epsilon_;
  FourierTransform transform_;
  int nb_;
  Eigen::VectorXd x2_, f_, coeffs_;
  Eigen::MatrixXd linear_;
  Eigen::VectorXd forcing_;
};

TEST(Scenes, CubicDaeEqualsTheExplicitSubstitution) {
  for (const double omega : {0.5, 0.7, 1.2}) {
    const Solved dae = solveScene("cubic.toml", true, {"harmonic_balance.omega=" + std::to_string(omega)},
                                  "dogleg-newton");
    ASSERT_TRUE(dae.result.converged()) << dae.result.summary();
    ExplicitCubic explicit_system(dae.model, 0.5);
    SolverOptions options;
    options.residual_tolerance = 1e-12;
    // The classical start: the linear response.
    const SolverResult r = makeSolver("dogleg-newton")
                               ->solve(explicit_system, explicit_system.linearResponse(), options);
    ASSERT_TRUE(r.converged()) << "omega " << omega << ": " << r.summary();
    const int nb = dae.model.basis.size();
    EXPECT_LT((r.solution - dae.full.head(2 * nb)).cwiseAbs().maxCoeff(), 1e-10) << "omega " << omega;
  }
}

}  // namespace
}  // namespace eqhb
