#include "eqhb/stability/monodromy_stability.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <unsupported/Eigen/MatrixFunctions>

#include "eqhb/error.h"
#include "eqhb/orbits/piecewise_linear_flow.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/references/time_integrator.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/stability/curve_stability.h"
#include "eqhb/stability/interface_reduction.h"
#include "eqhb/stability/phase_exponential.h"
#include "test_support.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/MatOp/SymShiftInvert.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <algorithm>

namespace eqhb {
namespace {

struct Comparison {
  HillResult monodromy, hill;
  orbits::ShootingResult exact;
};

// The monodromy's and Hill's verdicts and radii next to shooting's from the
// same harmonic-balance solution of `file` at ω with H harmonics.
Comparison compare(const std::string& file, double omega, int harmonics) {
  HbModel model = loadScene(test::problem(file), {"harmonic_balance.omega=" + std::to_string(omega)}).model;
  model.basis = HarmonicSet(model.basis.kind(), harmonics);
  model.samples = std::max(model.samples, samplesForHarmonics(model, harmonics));
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  Comparison c;
  MonodromyStability monodromy(model);
  c.monodromy = monodromy.analyse(omega, hb);
  c.hill = hillStability(model, hb);
  const orbits::PiecewiseLinearFlow flow(model, 0.0);
  c.exact = orbits::shootFromHarmonicBalance(flow, model, hb, orbits::ShootingOptions());
  EXPECT_TRUE(c.exact.converged) << c.exact.failure;
  std::printf("%s w=%.3f H=%d: monodromy %.6f (%.1f us), hill %.6f, exact %.6f\n", file.c_str(), omega, harmonics,
              c.monodromy.spectral_radius, 1e6 * c.monodromy.seconds, c.hill.spectral_radius, c.exact.spectral_radius);
  return c;
}

// Two points of friction-1d's arclength curve at its own H = 10 where the
// series rings: at 0.15926 its v flickers about 0 just after a stick ends,
// at 0.54648 it slows down to -0.36 without reaching 0 while its force
// overshoots the limit. Read as reversals, those samples gave radii 1.31
// and 1.04 (unstable) where shooting finds 0.43 and 0.84: a stick that ends
// slips against the holding force until v clearly slides, and a stick run
// whose v never reaches 0 is no reversal.
TEST(MonodromyStability, SeriesRingingIsNoReversal) {
  for (const double omega : {0.1592631123466103, 0.5464787739999302}) {
    const Comparison c = compare("friction-1d.toml", omega, 10);
    ASSERT_TRUE(c.monodromy.failure.empty()) << c.monodromy.failure;
    EXPECT_TRUE(c.exact.stable) << omega;
    EXPECT_EQ(c.monodromy.stable, c.exact.stable) << omega;
    EXPECT_NEAR(c.monodromy.spectral_radius, c.exact.spectral_radius, 0.12) << omega;
  }
}

// The two-mass chain (friction-1d) at H = 20. At ω = 0.55 the contact only
// reverses: the radius is within 1e-4 of the exact one (Hill's is 3e-3
// off). At 0.308 and 0.4 it sticks twice per period: the stick onsets are
// placed at the series' zero of v and the stick ends by the exact holding
// force; the radius is within 0.02 of the exact one (0.009 and 0.018 off).
TEST(MonodromyStability, StickSlipRadiusFollowsShooting) {
  const std::pair<double, double> cases[] = {{0.308, 0.02}, {0.4, 0.02}, {0.55, 1e-4}};
  for (const auto& [omega, tolerance] : cases) {
    const Comparison c = compare("friction-1d.toml", omega, 20);
    ASSERT_TRUE(c.monodromy.failure.empty()) << c.monodromy.failure;
    EXPECT_NEAR(c.monodromy.spectral_radius, c.exact.spectral_radius, tolerance) << omega;
    EXPECT_EQ(c.monodromy.stable, c.exact.stable) << omega;
    EXPECT_EQ(static_cast<int>(c.monodromy.exponents.size()), 4);
    EXPECT_EQ(c.monodromy.method, "monodromy");
  }
}

// Continuous sliding (reversals without stick): the saltation of the force's
// jump 2μN carries the whole effect of the friction (without it the radius
// would be the free oscillator's, 0.77; Hill's is 0.259 against the exact
// 0.2136, the monodromy's 0.2123).
TEST(MonodromyStability, ReversalRadiusFollowsShooting) {
  const Comparison c = compare("coulomb-oscillator.toml", 0.6, 20);
  EXPECT_NEAR(c.monodromy.spectral_radius, c.exact.spectral_radius, 2e-3);
  EXPECT_EQ(c.monodromy.stable, c.exact.stable);
}

// Cost signal (no timing): a point costs the syntheses of each law's
// velocity and force and at most one per holding-force series, not a sampling of
// every DOF; on odd harmonics half a period is propagated (Φ = Φ_h²), so a
// stick-slip orbit of friction-1d (two sticks, two slips a period) forms one
// exponential per phase of the half period, a reversal-only orbit one, and
// the holding forces are evaluated on the first half's samples only. Radii
// are the same when the curve's MonodromyStability is reused.
TEST(MonodromyStability, WorkPerPoint) {
  const std::pair<double, long> cases[] = {{0.308, 2}, {0.55, 1}};
  for (const auto& [omega, phases] : cases) {
    const HbModel model =
        loadScene(test::problem("friction-1d.toml"), {"harmonic_balance.omega=" + std::to_string(omega)}).model;
    const Eigen::VectorXd hb = test::harmonicBalance(model);
    MonodromyStability monodromy(model);
    const HillResult first = monodromy.analyse(omega, hb);
    const MonodromyStability::Work before = monodromy.work();
    const HillResult again = monodromy.analyse(omega, hb);
    const MonodromyStability::Work& after = monodromy.work();
    EXPECT_EQ(again.spectral_radius, first.spectral_radius) << omega;
    EXPECT_LE(after.syntheses - before.syntheses, 3) << omega;  // v, r, one holding series
    EXPECT_EQ(after.exponentials - before.exponentials, phases) << omega;
    EXPECT_LE(after.holding_forces - before.holding_forces, model.samples / 4) << omega;
  }
  // beam-damper at 2.8 slides through reversals only: each of its 5 laws'
  // holding forces is asked at one sample (the series' ringing read as a
  // short stick), summed from its series, so no holding series is
  // transformed: the syntheses are the laws' v and r alone.
  const HbModel beam = loadScene(test::problem("beam-damper.toml"), {"harmonic_balance.omega=2.8"}).model;
  const Eigen::VectorXd hb = test::harmonicBalance(beam);
  MonodromyStability monodromy(beam);
  monodromy.analyse(2.8, hb);
  EXPECT_GT(monodromy.work().holding_forces, 0);
  EXPECT_EQ(monodromy.work().syntheses, 2 * static_cast<long>(beam.laws.size()));
}

// An orbit stuck the whole period has one phase: its multipliers are
// exp(λT) of that phase's generator, here friction-1d with a limit no force
// reaches, DOF 2 held: DOF 1 alone, m ẍ + 2d ẋ + 2k x = f, whose pair is
// exp((−d/m ± i√(2k/m − (d/m)²)) T), and the held DOF's position and
// velocity, 1 and 1 (a stuck DOF stays where it is). The period is the
// whole one on odd harmonics too (not the half that is propagated).
TEST(MonodromyStability, StuckOrbitHasItsPhasesMultipliers) {
  const double omega = 0.4, period = 2.0 * M_PI / omega, m = 1.0, k = 1.0, d = 0.02;
  const HbModel model = loadScene(test::problem("friction-1d.toml"),
                                  {"harmonic_balance.omega=0.4", "law.muN=1000"}).model;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  MonodromyStability monodromy(model);
  const HillResult r = monodromy.analyse(omega, hb);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  EXPECT_EQ(monodromy.work().exponentials, 1);
  ASSERT_EQ(r.exponents.size(), 4u);
  const std::complex<double> pair =
      std::exp(std::complex<double>(-d / m, std::sqrt(2.0 * k / m - (d / m) * (d / m))) * period);
  std::vector<std::complex<double>> expected = {1.0, 1.0, pair, std::conj(pair)};
  for (const FloquetExponent& e : r.exponents) {
    auto nearest = std::min_element(expected.begin(), expected.end(), [&](const auto& x, const auto& y) {
      return std::abs(x - e.multiplier) < std::abs(y - e.multiplier);
    });
    EXPECT_LE(std::abs(*nearest - e.multiplier), 1e-9) << e.multiplier;
    expected.erase(nearest);
  }
  EXPECT_TRUE(r.stable);  // neutral: a radius of 1 within the unit tolerance
}

// The default monodromy and one with `other` options at the same
// harmonic-balance solution of `file` at ω, with their work.
struct TwoWays {
  HillResult usual, other;
  long usual_exponentials = 0, other_exponentials = 0;
  int propagated_dofs = 0;
};
TwoWays analyseTwoWays(const std::string& file, double omega, const MonodromyReduction& other) {
  const HbModel model = loadScene(test::problem(file), {"harmonic_balance.omega=" + std::to_string(omega)}).model;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  MonodromyStability usual(model), changed(model, HillOptions().unit_tolerance, other);
  TwoWays out{usual.analyse(omega, hb), changed.analyse(omega, hb)};
  EXPECT_TRUE(out.usual.failure.empty()) << out.usual.failure;
  EXPECT_TRUE(out.other.failure.empty()) << out.other.failure;
  out.usual_exponentials = usual.work().exponentials;
  out.other_exponentials = changed.work().exponentials;
  out.propagated_dofs = usual.propagatedDofs();
  return out;
}

// Half a period on odd harmonics (Φ = Φ_h², header) against the whole
// period's product: the same multipliers, each of them, on a stick-slip and a
// reversal-only orbit of friction-1d, the reduced beam-damper (one point
// stable, one near its resonance) and the large beam's leading-modes chain,
// with half the exponentials. A wrong reading of the span's wrap (the first
// switch met with the slip directions swapped) changes the saltation there.
TEST(MonodromyStability, HalfPeriodHasTheWholePeriodsMultipliers) {
  const std::pair<const char*, double> cases[] = {
      {"friction-1d.toml", 0.308}, {"friction-1d.toml", 0.55}, {"beam-damper.toml", 2.8},
      {"beam-damper.toml", 3.5},   {"beam-joint-large.toml", 3.25}};
  MonodromyReduction whole_period;
  whole_period.half_period = false;
  for (const auto& [file, omega] : cases) {
    const TwoWays two = analyseTwoWays(file, omega, whole_period);
    const HillResult &a = two.usual, &b = two.other;
    ASSERT_EQ(a.exponents.size(), b.exponents.size()) << file << " " << omega;
    EXPECT_EQ(a.stable, b.stable) << file << " " << omega;
    EXPECT_NEAR(a.spectral_radius, b.spectral_radius, 1e-9 * b.spectral_radius) << file << " " << omega;
    // Each multiplier of the whole product has one of the half's next to it.
    for (const FloquetExponent& e : b.exponents) {
      double nearest = INFINITY;
      for (const FloquetExponent& f : a.exponents) nearest = std::min(nearest, std::abs(f.multiplier - e.multiplier));
      EXPECT_LE(nearest, 1e-8 * std::max(1.0, std::abs(e.multiplier))) << file << " " << omega << " " << e.multiplier;
    }
    EXPECT_EQ(2 * two.usual_exponentials, two.other_exponentials) << file << " " << omega;
    std::printf("%s w=%.3f: radius %.12f (half period), %.12f (whole), exponentials %ld / %ld\n", file, omega,
                a.spectral_radius, b.spectral_radius, two.usual_exponentials, two.other_exponentials);
  }
}

// A large structure is propagated on its law DOFs and the modes that
// matter: beam-damper's 120 DOFs keep the free beam's first three
// frequencies within 0.5 % in far fewer coordinates, and at resonance the
// reduced monodromy's verdict and radius agree with Hill's.
TEST(MonodromyStability, ReducedBeamAgreesWithHill) {
  const HbModel model = loadScene(test::problem("beam-damper.toml"), {"harmonic_balance.omega=3.5"}).model;
  std::vector<int> dofs;
  for (const AttachedLaw& a : model.laws) dofs.push_back(a.attachment.dof(0));
  const Eigen::MatrixXd mass(model.structure.mass), stiffness(model.structure.stiffness);
  const InterfaceReduction reduced =
      reduceToInterface(mass, Eigen::MatrixXd(model.structure.damping), stiffness, dofs, 3.0 * 9 * 3.5, 2.0 * M_PI / 3.5);
  EXPECT_LT(reduced.mass.rows(), 12);
  EXPECT_GT(reduced.modes_dropped, 100);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> full(stiffness, mass), small(reduced.stiffness, reduced.mass);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(std::sqrt(small.eigenvalues()[k] / full.eigenvalues()[k]), 1.0, 5e-3) << k;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  MonodromyStability monodromy(model);
  const HillResult m = monodromy.analyse(3.5, hb), h = hillStability(model, hb);
  ASSERT_TRUE(m.failure.empty()) << m.failure;
  EXPECT_EQ(m.stable, h.stable);
  EXPECT_NEAR(m.spectral_radius, h.spectral_radius, 0.01);
  EXPECT_EQ(m.state_dimension, 2 * static_cast<int>(reduced.mass.rows()));
}

// A real-size structure is reduced on its sparse matrices: beam-joint-large
// (2000 DOFs, 50 friction nodes) keeps its 50 law DOFs and the few slow
// fixed-interface modes (found by shift-invert Lanczos, not a dense
// eigensolver of 1950 modes: 11 s before), and its three lowest
// frequencies within 0.5 % of the full structure's.
TEST(MonodromyStability, LargeBeamIsReducedOnItsSparseMatrices) {
  const HbModel model = loadScene(test::problem("beam-joint-large.toml")).model;
  std::vector<int> dofs;
  for (const AttachedLaw& a : model.laws) dofs.push_back(a.attachment.dof(0));
  const LinearStructure& s = model.structure;
  const double omega = model.omega;
  const InterfaceReduction reduced =
      reduceToInterface(s.mass, s.damping, s.stiffness, dofs, 3.0 * 13 * omega, 2.0 * M_PI / omega);
  EXPECT_EQ(static_cast<int>(reduced.boundary.size()), 50);
  EXPECT_GE(reduced.modes_kept, 1);
  EXPECT_LE(reduced.modes_kept, 10);
  EXPECT_EQ(reduced.modes_kept + reduced.modes_dropped + 50, s.dofs());
  EXPECT_LT((reduced.projection * reduced.basis - Eigen::MatrixXd::Identity(reduced.mass.rows(), reduced.mass.rows()))
                .norm(),
            1e-9);
  using Operator = Spectra::SymShiftInvert<double, Eigen::Sparse, Eigen::Sparse>;
  Operator op(s.stiffness, s.mass);
  Spectra::SparseSymMatProd<double> m(s.mass);
  Spectra::SymGEigsShiftSolver<Operator, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert> full(
      op, m, 3, 20, 0.0);
  full.init();
  full.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  ASSERT_EQ(full.info(), Spectra::CompInfo::Successful);
  Eigen::VectorXd lowest = full.eigenvalues();
  std::sort(lowest.data(), lowest.data() + lowest.size());
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> small(reduced.stiffness, reduced.mass);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(std::sqrt(small.eigenvalues()[k] / lowest[k]), 1.0, 5e-3) << k;
}

// The product carried in the phases' leading modes has the whole Φ's
// multipliers: on the large beam (104 propagated states, 50 friction laws)
// at ω = 3.25, between the curve's two Neimark–Sacker points (unstable), and
// at 3.5 (stable), and on the small propagations that now take it too
// (beam-damper's 12 states, friction-1d's 4): the same verdict and radius
// to 1e-9.
TEST(MonodromyStability, LeadingModesChainIsTheWholeProduct) {
  MonodromyReduction whole;
  whole.leading_modes = false;
  const std::pair<const char*, double> cases[] = {
      {"beam-joint-large.toml", 3.25}, {"beam-joint-large.toml", 3.5}, {"beam-damper.toml", 2.8},
      {"friction-1d.toml", 0.308}};
  for (const auto& [file, omega] : cases) {
    const TwoWays two = analyseTwoWays(file, omega, whole);
    const HillResult &a = two.usual, &b = two.other;
    if (std::string(file) == "beam-joint-large.toml") {
      EXPECT_GT(two.propagated_dofs, 50);
    }
    EXPECT_EQ(a.stable, b.stable) << file << " " << omega;
    EXPECT_NEAR(a.spectral_radius, b.spectral_radius, 1e-9) << file << " " << omega;
    EXPECT_EQ(two.usual_exponentials, two.other_exponentials) << file << " " << omega;
    std::printf("%s w=%.2f: radius %.9f (leading modes), %.9f (whole), stable %d\n", file, omega,
                a.spectral_radius, b.spectral_radius, a.stable ? 1 : 0);
  }
}

// The reduction on the laws' own coordinates (interface_reduction.h): a
// 30-mass chain with laws between masses (one reading 0.6 x4 + 0.8 x9, one
// reading the negative of another's coordinate). P T = I, each law's
// coordinate is one entry of q, and with every mode kept the reduced
// structure has the full one's frequencies; keeping the slow ones, its
// lowest three within 0.5 %, in 4 law coordinates and 6 modes.
TEST(MonodromyStability, ReductionOnTheLawsCoordinates) {
  const int n = 30;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n), m = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    k(i, i) = 200.0;
    if (i + 1 < n) k(i, i + 1) = k(i + 1, i) = -100.0;
    m(i, i) = 1.0 + 0.1 * (i % 3);
  }
  const Eigen::MatrixXd c = 0.02 * k;  // σ = 0.01 ω²: the modes above ω² = 66 decay past e^-13.8 a period
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(n, 4);
  w(10, 0) = 1.0;
  w(11, 0) = -1.0;  // between masses 11 and 12
  w(20, 1) = 1.0;
  w(25, 1) = -1.0;
  w(4, 2) = 0.6;
  w(9, 2) = 0.8;
  w(2, 3) = 1.0;  // grounded
  const double period = 2.0 * M_PI / 0.3;
  const auto exact = reduceToLawCoordinates(m, c, k, w, 1e9, period, 1e9);  // every mode kept
  ASSERT_TRUE(exact.has_value());
  const InterfaceReduction& all = exact->reduction;
  EXPECT_EQ(all.mass.rows(), n);
  EXPECT_LT((all.projection * all.basis - Eigen::MatrixXd::Identity(n, n)).norm(), 1e-12);
  for (int j = 0; j < 4; ++j) {
    const Eigen::RowVectorXd reads = w.col(j).transpose() * all.basis;  // u_j in q
    EXPECT_NEAR(reads[exact->coordinate[j]], 1.0, 1e-13) << j;
    EXPECT_NEAR(reads.norm(), 1.0, 1e-13) << j;
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> full(k, m), same(all.stiffness, all.mass);
  for (int i = 0; i < n; ++i) EXPECT_NEAR(same.eigenvalues()[i] / full.eigenvalues()[i], 1.0, 1e-10) << i;

  const auto slow = reduceToLawCoordinates(m, c, k, w, 3.0 * 0.3, period);
  ASSERT_TRUE(slow.has_value());
  const InterfaceReduction& few = slow->reduction;
  EXPECT_LT(few.mass.rows(), n / 2);
  EXPECT_GT(few.modes_kept, 0);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> small(few.stiffness, few.mass);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::sqrt(small.eigenvalues()[i] / full.eigenvalues()[i]), 1.0, 5e-3) << i;
  std::printf("chain: %d coordinates (%d modes)\n", static_cast<int>(few.mass.rows()), few.modes_kept);
  EXPECT_LT((few.projection * few.basis - Eigen::MatrixXd::Identity(few.mass.rows(), few.mass.rows())).norm(), 1e-12);

  // A direction that repeats another (or is a combination of others) has no
  // coordinate of its own: the caller passes distinct ones.
  Eigen::MatrixXd dependent(n, 2);
  dependent << w.col(0), -2.0 * w.col(0);
  EXPECT_FALSE(reduceToLawCoordinates(m, c, k, dependent, 1.0, period).has_value());
}

// Where the reduced and Hill's radii disagree (beam-damper at ω = 2.8:
// 0.244 against 0.499 on the whole beam, 0.352 on Hill's reduction to the
// modes within its band), the time-domain orbit started from the
// harmonic-balance one settles at the reduced radius's rate: its
// period-start change falls from 1.0e-2 to 8.5e-10 over periods 2 to 12, a
// ratio of 0.196 a period (0.499 would take it to ~1e-5). Keeping more modes
// moves the reduced radius by 1.3e-3. The unreduced propagation is no
// reference here: in double precision its 240 x 240 product gives 0.956
// (MonodromyReduction{full_dofs = 120}), 0.830 in the reduced coordinates
// with every mode kept.
TEST(MonodromyStability, ReducedBeamRadiusIsTheTimeDomainDecayRate) {
  const HbModel model = loadScene(test::problem("beam-damper.toml"), {"harmonic_balance.omega=2.8"}).model;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  MonodromyStability reduced(model);
  const HillResult r = reduced.analyse(2.8, hb);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  EXPECT_LT(reduced.propagatedDofs(), 12);
  MonodromyReduction more;
  more.decay = 100.0;  // fast modes kept down to a free multiplier of e^-100
  MonodromyStability wider(model, HillOptions().unit_tolerance, more);
  const HillResult w = wider.analyse(2.8, hb);
  EXPECT_GT(wider.propagatedDofs(), reduced.propagatedDofs());
  EXPECT_NEAR(r.spectral_radius, w.spectral_radius, 5e-3);

  TimeOptions time;
  time.max_periods = 12;
  time.periodic_tolerance = 1e-15;  // never met: every period runs
  std::vector<double> change;
  integrateToSteadyState(model, time, hb, [&](int, double c) { change.push_back(c); });
  ASSERT_EQ(change.size(), 12u);
  // From period 2 on (the first carries the start's truncation error) to
  // 12, before the change reaches the integrator's floor (~3e-11).
  const double rate = std::pow(change[11] / change[1], 1.0 / 10.0);
  std::printf("beam-damper w=2.8: reduced %.6f (%d dofs), %.6f (%d dofs), time-domain rate %.4f\n",
              r.spectral_radius, reduced.propagatedDofs(), w.spectral_radius, wider.propagatedDofs(), rate);
  EXPECT_LT(std::abs(std::log(r.spectral_radius / rate)), std::log(1.5));
}

TEST(MonodromyStability, RejectsUnsupportedLawsAndBadInput) {
  const HbModel cubic = loadScene(test::problem("cubic.toml")).model;
  EXPECT_FALSE(MonodromyStability::supports(cubic));
  EXPECT_THROW(MonodromyStability{cubic}, InputError);
  const HbModel friction = loadScene(test::problem("friction-1d.toml")).model;
  MonodromyStability monodromy(friction);
  EXPECT_THROW(monodromy.analyse(0.4, Eigen::VectorXd::Zero(3)), InputError);
  EXPECT_THROW(monodromy.analyse(-1.0, Eigen::VectorXd::Zero(3)), InputError);
}

// "auto" takes the monodromy where it applies (small structures with
// supported laws), Hill elsewhere; an unknown method names its field.
TEST(MonodromyStability, MethodChoice) {
  HbModel friction = loadScene(test::problem("friction-1d.toml")).model;
  const Eigen::VectorXd hb = test::harmonicBalance(friction);
  HillOptions options;
  options.method = "auto";
  EXPECT_EQ(analyseStability(friction, hb, options).method, "monodromy");
  options.method = "hill";
  EXPECT_EQ(analyseStability(friction, hb, options).method, "hill");
  const HbModel cubic = loadScene(test::problem("cubic.toml")).model;
  options.method = "auto";
  EXPECT_EQ(analyseStability(cubic, test::harmonicBalance(cubic), options).method, "hill");
  options.method = "monodromy";
  EXPECT_THROW(analyseStability(cubic, test::harmonicBalance(cubic), options), InputError);
  options.method = "floquet";
  try {
    analyseStability(friction, hb, options);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stability_method"), std::string::npos) << e.what();
  }
}

// The decomposed exponential of a phase equals Eigen's scaling-and-squaring
// one; a defective generator (a free mass: a Jordan block at 0) is not
// decomposed and takes the exponential itself.
TEST(MonodromyStability, PhaseExponentialMatchesTheMatrixExponential) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(6, 6);
  Eigen::Matrix3d k;
  k << 2.0, -1.0, 0.0, -1.0, 2.0, -1.0, 0.0, -1.0, 1.5;
  a.topRightCorner(3, 3).setIdentity();
  a.bottomLeftCorner(3, 3) = -k;
  a.bottomRightCorner(3, 3) = -0.02 * Eigen::Matrix3d::Identity() - 0.01 * k;
  a(3, 5) = 0.3;  // a non-symmetric coupling, as a slider's anchor gives
  const PhaseExponential fast(a);
  EXPECT_TRUE(fast.decomposed());
  Eigen::MatrixXd phi = Eigen::MatrixXd::Random(6, 6), scratch;
  const Eigen::MatrixXd start = phi;
  for (double tau : {0.01, 0.7, 3.0, 25.0}) {
    const Eigen::MatrixXd reference = (a * tau).exp();
    EXPECT_LT((fast.exponential(tau) - reference).norm(), 1e-12 * reference.norm()) << tau;
  }
  fast.apply(0.7, phi, scratch);
  const Eigen::MatrixXd reference = (a * 0.7).exp() * start;
  EXPECT_LT((phi - reference).norm(), 1e-12 * reference.norm());

  Eigen::MatrixXd free = Eigen::MatrixXd::Zero(2, 2);
  free(0, 1) = 1.0;
  const PhaseExponential jordan(free);
  EXPECT_FALSE(jordan.decomposed());
  EXPECT_EQ(jordan.exponential(2.0), (free * 2.0).exp());
}

// The modes come by decreasing real part: those a phase of length τ keeps
// above kNegligibleGrowth are a leading set, e^{λτ} are exp(A τ)'s
// eigenvalues, and scaling the leading rows alone is exp(D τ) on them.
TEST(MonodromyStability, PhaseExponentialKeepsTheLeadingModes) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4, 4);
  a.topRightCorner(2, 2).setIdentity();
  a.bottomLeftCorner(2, 2) << -1.0, 0.0, 0.0, -1e4;  // ω 1 and 100
  a.bottomRightCorner(2, 2) << -0.02, 0.0, 0.0, -20.0;  // decay rates 0.01 and 10
  const PhaseExponential phase(a);
  ASSERT_TRUE(phase.decomposed());
  EXPECT_EQ(phase.survivingModes(1.0), 4);
  EXPECT_EQ(phase.survivingModes(10.0), 2);  // e^{-100} is gone, e^{-0.1} is not
  Eigen::VectorXcd multipliers(4);
  phase.multipliers(10.0, multipliers);
  const Eigen::VectorXcd expected = Eigen::EigenSolver<Eigen::MatrixXd>((a * 10.0).exp(), false).eigenvalues();
  for (Eigen::Index i = 0; i < 4; ++i)
    EXPECT_LT((expected.array() - multipliers[i]).abs().minCoeff(), 1e-10) << multipliers[i];  // expm at ‖Aτ‖ ~ 1e5
  EXPECT_NEAR(std::abs(multipliers[0]), std::exp(-0.1), 1e-12);  // the slow mode leads
  Eigen::MatrixXd all = Eigen::MatrixXd::Random(4, 3);
  Eigen::MatrixXd leading = all.topRows(2);
  phase.scaleModes(0.5, all);
  phase.scaleModes(0.5, leading);
  EXPECT_EQ(leading, all.topRows(2));
}

}  // namespace
}  // namespace eqhb
