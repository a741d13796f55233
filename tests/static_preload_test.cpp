// Static preload (preload/static_contact.h, [[preload]] in scenes): the
// static contact solve against closed forms (a spring pressed on a penalty
// wall, a Jenkins slider that sticks or slips), the operating point of the
// dynamic solve (a preloaded stuck joint under small forcing is the linear
// stuck system, its mean fixed by the static state) and the input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <unistd.h>

#include "eqhb/app/modes.h"
#include "eqhb/app/solve.h"
#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/error.h"
#include "eqhb/output/solution_json.h"
#include "test_support.h"

namespace eqhb {
namespace {

// A 1-DOF oscillator (m = 1, k = 1, d = 0.02) with one law and `extra` TOML.
std::string oscillator(const std::string& law, const std::string& extra, const std::string& set = "all") {
  return "name = \"preloaded\"\n[structure]\ntype = \"chain\"\ndofs = 1\nm = 1.0\nk = 1.0\nd = 0.02\n" + law +
         extra + "[harmonic_balance]\nharmonics = 5\nset = \"" + set + "\"\nsamples = 64\nomega = 1.5\n";
}

const char* kWall = "[[law]]\ntype = \"penalty-contact\"\ndofs = [1]\nstiffness = 10.0\ngap = 0.5\n";
const char* kJenkins = "[[law]]\ntype = \"jenkins\"\nformulation = \"aft\"\ndofs = [1]\nmuN = 1.0\nk_t = 4.0\n";

std::string preload(double force) { return "[[preload]]\ndof = 1\nforce = " + formatNumber(force) + "\n"; }
std::string forcing(double amplitude, int harmonic = 1) {
  return "[[forcing]]\ndof = 1\nharmonic = " + std::to_string(harmonic) + "\ncos = " + formatNumber(amplitude) + "\n";
}

app::SceneSettings written(const std::string& text) {
  // Each test runs in its own process (ctest -j), and other test runs may
  // share the temporary folder: the file names carry the test's and the process's.
  static int count = 0;
  const std::string path = ::testing::TempDir() + "/preload_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                           std::to_string(::getpid()) + "_" + std::to_string(count++) + ".toml";
  std::ofstream(path) << text;
  app::SceneSettings s;
  s.path = path;
  return s;
}

Scene settled(const std::string& text) { return app::loadScene(written(text)); }

// The message of the InputError that loading `text` throws ("" if none).
std::string refusal(const std::string& text) {
  try {
    settled(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Pressed on the wall: k x = F − k_n (x − g0), x = (F + k_n g0)/(k + k_n).
TEST(StaticPreload, SpringOnPenaltyWallIsTheClosedForm) {
  const double k = 1.0, k_n = 10.0, g0 = 0.5, force = 2.0;
  const Scene s = settled(oscillator(kWall, preload(force)));
  ASSERT_TRUE(s.at_rest);
  const double x = (force + k_n * g0) / (k + k_n);
  EXPECT_NEAR(s.at_rest->displacement[0], x, 1e-12);
  const StaticStatus& status = *s.at_rest->status[0];
  EXPECT_EQ(std::string(staticStateName(status.state)), "closed");
  EXPECT_NEAR(*status.normal_force, k_n * (x - g0), 1e-12);
  EXPECT_NEAR(*status.gap, g0 - x, 1e-12);
  // Below the gap the wall is not reached: x = F/k, no force.
  const Scene open = settled(oscillator(kWall, preload(0.3)));
  EXPECT_NEAR(open.at_rest->displacement[0], 0.3, 1e-12);
  EXPECT_EQ(std::string(staticStateName(open.at_rest->status[0]->state)), "open");
  EXPECT_NEAR(*open.at_rest->status[0]->normal_force, 0.0, 1e-12);
  EXPECT_NEAR(*open.at_rest->status[0]->gap, 0.2, 1e-12);
}

// A slider loaded from rest sticks while k_t x <= μN (x = F/(k + k_t)), and
// slips to the limit beyond (k x = F − μN).
TEST(StaticPreload, JenkinsSticksOrSlipsFromRest) {
  const Scene stuck = settled(oscillator(kJenkins, preload(1.0)));
  EXPECT_NEAR(stuck.at_rest->displacement[0], 1.0 / 5.0, 1e-12);
  EXPECT_EQ(std::string(staticStateName(stuck.at_rest->status[0]->state)), "stuck");
  EXPECT_NEAR(*stuck.at_rest->status[0]->tangential_force, 0.8, 1e-12);
  const Scene slipping = settled(oscillator(kJenkins, preload(2.0)));
  EXPECT_NEAR(slipping.at_rest->displacement[0], 1.0, 1e-12);
  EXPECT_EQ(std::string(staticStateName(slipping.at_rest->status[0]->state)), "slipping");
  EXPECT_NEAR(*slipping.at_rest->status[0]->tangential_force, 1.0, 1e-12);
}

// The coefficients of x on the one DOF: [x0, a1, b1, a2, b2, ...].
Eigen::VectorXd solveDisplacement(const std::string& text, std::string* start = nullptr) {
  app::SolveOptions o;
  const app::Solution s = app::solve(written(text), o);
  EXPECT_TRUE(s.converged()) << terminationName(s.run.result.termination);
  if (start) *start = s.run.start;
  return s.full.head(s.model().basis.size());
}

// The linear 1-DOF response to f cos ωt with stiffness k: (a1, b1).
Eigen::Vector2d linear(double k, double f, double omega = 1.5, double d = 0.02) {
  Eigen::Matrix2d a;
  a << k - omega * omega, omega * d, -omega * d, k - omega * omega;
  return a.fullPivLu().solve(Eigen::Vector2d(f, 0.0));
}

// Preloaded and stuck, a small forcing never slips the slider: the response
// is the linear system with k + k_t about the static state (mean F/(k + k_t)).
// The unanchored slider (the same constant load as forcing, no static
// solve) sticks at the period's mean instead and carries no static force:
// mean F/k.
TEST(StaticPreload, StuckJointUnderSmallForcingIsTheLinearStuckSystem) {
  const double f = 0.01;
  std::string start;
  const Eigen::VectorXd x = solveDisplacement(oscillator(kJenkins, preload(1.0) + forcing(f)), &start);
  EXPECT_EQ(start, "preload");
  EXPECT_NEAR(x[0], 1.0 / 5.0, 1e-10);
  const Eigen::Vector2d stuck = linear(5.0, f);
  EXPECT_NEAR(x[1], stuck[0], 1e-10);
  EXPECT_NEAR(x[2], stuck[1], 1e-10);
  EXPECT_LT(x.tail(x.size() - 3).cwiseAbs().maxCoeff(), 1e-10);
  const Eigen::VectorXd free_mean = solveDisplacement(oscillator(kJenkins, forcing(1.0, 0) + forcing(f)));
  EXPECT_NEAR(free_mean[0], 1.0, 1e-10);
}

// Pressed on the wall and shaken gently, the contact stays closed: the
// linear system with k + k_n about the static state.
TEST(StaticPreload, PressedWallUnderSmallForcingIsTheLinearSystem) {
  const double f = 0.01;
  const Eigen::VectorXd x = solveDisplacement(oscillator(kWall, preload(2.0) + forcing(f)));
  EXPECT_NEAR(x[0], 7.0 / 11.0, 1e-10);
  const Eigen::Vector2d pressed = linear(11.0, f);
  EXPECT_NEAR(x[1], pressed[0], 1e-10);
  EXPECT_NEAR(x[2], pressed[1], 1e-10);
}

// Two masses pressed together by equal and opposite preloads through a
// relative penalty contact, shaken gently: the contact stays closed, so the
// response linearised about the static state (the solve's start) is the
// answer. From the static state itself the condensed system's first iterate
// moves the masses under the static contact force alone, which opens the
// contact, and the solve stalled (not_progressing after 53 iterations).
TEST(StaticPreload, PressedPairStartsFromTheLinearisedResponse) {
  const std::string text =
      "name = \"pair\"\n[structure]\ntype = \"chain\"\ndofs = 2\nm = 1.0\nk = 1.0\nd = 0.02\n"
      "[[forcing]]\ndof = 1\nharmonic = 1\ncos = 0.1\n[[preload]]\ndof = 1\nforce = 1.0\n[[preload]]\ndof = 2\n"
      "force = -1.0\n[[law]]\ntype = \"penalty-contact\"\nbetween = [1, 2]\nstiffness = 10.0\ngap = 0.0\n"
      "[harmonic_balance]\nharmonics = 5\nset = \"all\"\nsamples = 64\nomega = 1.3\n";
  app::SolveOptions o;
  o.fallback = "none";
  const app::Solution s = app::solve(written(text), o);
  ASSERT_TRUE(s.converged()) << terminationName(s.run.result.termination);
  EXPECT_EQ(s.run.start, "preload");
  EXPECT_LE(s.run.result.iterations, 1);
}

// A velocity-level friction law (no slider state of its own) stuck over the
// whole period allows any mean within its friction limit: history decides.
// Under a [[preload]] the history is the static state, stuck from rest, and
// the dynamic solve keeps it: a 2-DOF chain (K = k [[2, -1], [-1, 1]]) whose
// first DOF is held by friction (limit 1) while the preload pulls the second
// with 0.5 and a small forcing shakes it. Stuck, the first DOF stays at 0
// over the whole period (the static state) and the second is the 1-DOF
// oscillator clamped at the first, about its static 0.5. The same load as a
// constant forcing term, solved from zero, has no static state to keep.
TEST(StaticPreload, VelocityLevelFrictionStuckFromRestKeepsTheStaticMean) {
  const double f = 0.01;
  const std::string chain =
      "name = \"held\"\n[structure]\ntype = \"chain\"\ndofs = 2\nm = 1.0\nk = 1.0\nd = 0.02\n"
      "[[forcing]]\ndof = 2\nharmonic = 1\ncos = " + formatNumber(f) + "\n";
  const std::string settings = "[harmonic_balance]\nharmonics = 5\nset = \"all\"\nsamples = 64\nomega = 1.5\n";
  const std::string pull = "[[preload]]\ndof = 2\nforce = 0.5\n";
  const Eigen::Vector2d clamped = linear(1.0, f);
  for (const std::string law : {"[[law]]\ntype = \"coulomb-1d\"\ndofs = [1]\nmuN = 1.0\n",
                                "[[law]]\ntype = \"stribeck\"\ndofs = [1]\nmuN_dynamic = 1.0\nmuN_static = 1.2\n"
                                "v_s = 0.1\n"}) {
    app::SolveOptions o;
    o.fallback = "none";
    const app::Solution s = app::solve(written(chain + pull + law + settings), o);
    ASSERT_TRUE(s.converged()) << law << terminationName(s.run.result.termination);
    EXPECT_EQ(s.run.start, "preload");
    ASSERT_TRUE(s.run.scene.at_rest);
    EXPECT_NEAR(s.run.scene.at_rest->displacement[0], 0.0, 1e-12) << law;
    EXPECT_NEAR(s.run.scene.at_rest->displacement[1], 0.5, 1e-12) << law;
    const int size = s.model().basis.size();  // [x0, a1, b1, ...] per DOF
    const Eigen::VectorXd held = s.full.head(size), shaken = s.full.segment(size, size);
    EXPECT_LT(held.cwiseAbs().maxCoeff(), 1e-12) << law;  // the static mean, not moving
    EXPECT_NEAR(shaken[0], 0.5, 1e-12) << law;
    EXPECT_NEAR(shaken[1], clamped[0], 1e-10) << law;
    EXPECT_NEAR(shaken[2], clamped[1], 1e-10) << law;
    // The pull as a constant forcing term instead: a stuck solution too,
    // but about another mean (0.5 here: the friction carries nothing on
    // average), which is what the static solve fixes.
    const std::string constant = "[[forcing]]\ndof = 2\nharmonic = 0\ncos = 0.5\n";
    const app::Solution free = app::solve(written(chain + constant + law + settings), o);
    ASSERT_TRUE(free.converged()) << law;
    EXPECT_GT(std::abs(free.full[0]), 0.1) << law;
  }
  // A contact with friction pressed by a bolt-like preload (normal DOF 1)
  // and loaded sideways (DOF 2) before the shaking: stuck and closed over the
  // whole period at the static state, its forces the static ones on average.
  const std::string pressed =
      "name = \"pressed\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0, 0.0], [0.0, 1.0]]\n"
      "damping = [[0.05, 0.0], [0.0, 0.05]]\nstiffness = [[1.0, 0.3], [0.3, 1.0]]\n"
      "[[forcing]]\ndof = 2\nharmonic = 1\ncos = 0.01\n[[preload]]\ndof = 1\nforce = 2.0\n[[preload]]\ndof = 2\n"
      "force = 0.3\n[[law]]\ntype = \"contact-friction\"\ndofs = [1, 2]\nmu = 0.5\npreload = 0.0\n";
  app::SolveOptions o;
  o.fallback = "none";
  const app::Solution s = app::solve(written(pressed + settings), o);
  ASSERT_TRUE(s.converged()) << terminationName(s.run.result.termination);
  const StaticStatus& status = *s.run.scene.at_rest->status[0];
  EXPECT_EQ(std::string(staticStateName(status.state)), "stuck");
  const int size = s.model().basis.size();
  EXPECT_LT(s.full.head(2 * size).cwiseAbs().maxCoeff(), 1e-12);  // x = 0 on both DOFs, all harmonics
  const int n = s.model().structure.dofs();
  EXPECT_NEAR(std::abs(s.full[n * size]), *status.normal_force, 1e-10);            // λ_n's mean
  EXPECT_NEAR(std::abs(s.full[(n + 1) * size]), *status.tangential_force, 1e-10);  // λ_t's mean
}

TEST(StaticPreload, SolveJsonReportsTheStaticState) {
  app::SolveOptions o;
  const app::Solution s = app::solve(written(oscillator(kWall, preload(2.0) + forcing(0.01))), o);
  const nlohmann::json j = output::solutionJson(s, false);
  ASSERT_TRUE(j.contains("preload"));
  EXPECT_TRUE(j["preload"]["converged"].get<bool>());
  EXPECT_EQ(j["preload"]["elements"][0]["state"], "closed");
  EXPECT_NEAR(j["preload"]["elements"][0]["normal_force"].get<double>(), 10.0 * (7.0 / 11.0 - 0.5), 1e-12);
  EXPECT_NEAR(j["preload"]["elements"][0]["gap"].get<double>(), 0.5 - 7.0 / 11.0, 1e-12);
}

// A nonlinear mode vibrates about the static state its constant loads set:
// pressed on the wall (a [[preload]], or a constant [[forcing]] term) the
// oscillator's small-amplitude mode is the pressed one, ω = √(k + k_n) = √11,
// not the free one at rest (ω = 1, the wall 0.5 away).
TEST(StaticPreload, NonlinearModeVibratesAboutTheStaticState) {
  for (const std::string& load : {preload(2.0), forcing(2.0, 0)}) {
    app::ModesOptions o;
    o.from = 1e-4;
    o.to = 1e-3;
    o.points = 3;
    const app::ModesRun run = app::modes(written(oscillator(kWall, load)), o);
    ASSERT_TRUE(run.backbone.complete()) << load;
    ASSERT_TRUE(run.scene.at_rest) << load;
    EXPECT_NEAR(run.backbone.start.omega, std::sqrt(11.0), 1e-12) << load;
    for (const BackbonePoint& p : run.backbone.points) EXPECT_NEAR(p.omega, std::sqrt(11.0), 1e-9) << load;
    EXPECT_NEAR(run.scene.at_rest->displacement[0], 7.0 / 11.0, 1e-12) << load;
  }
}

TEST(StaticPreload, BadInputNamesTheField) {
  EXPECT_NE(refusal(oscillator(kWall, "[[preload]]\ndof = 2\nforce = 1.0\n")).find("preload[0].dof"),
            std::string::npos);
  EXPECT_NE(refusal(oscillator(kWall, "[[preload]]\ndof = 1\nforce = nan\n")).find("preload[0].force"),
            std::string::npos);
  EXPECT_NE(refusal(oscillator(kWall, "[[preload]]\ndof = 1\n")).find("preload[0].force"), std::string::npos);
  EXPECT_NE(refusal(oscillator(kWall, preload(1.0), "odd")).find("preload[0]"), std::string::npos);
  // A free mass pulled away from its wall: nothing holds it.
  std::string free_mass = oscillator(kWall, preload(-1.0));
  free_mass.replace(free_mass.find("k = 1.0"), 7, "k = 0.0");
  const std::string held = refusal(free_mass);
  EXPECT_NE(held.find("preload"), std::string::npos) << held;
  EXPECT_NE(held.find("no contact holds"), std::string::npos) << held;
}

// A static solve that stops short is told apart by whether the structure
// alone holds the load: a spring-held mass has a static state the solvers
// did not find (StaticSolveFailed, a solve that did not converge), a free
// mass pulled from its wall has none (InputError naming preload). One
// iteration allowed: neither converges.
TEST(StaticPreload, AStaticSolveThatStopsSaysWhetherAStateExists) {
  SolverOptions one_step;
  one_step.max_iterations = 1;
  auto dogleg = makeSolver("dogleg");
  const Scene held = app::loadScene(written(oscillator(kJenkins, forcing(2.0, 0))));
  EXPECT_THROW(solveStaticContact(held.model, *dogleg, one_step), StaticSolveFailed);
  std::string free_mass = oscillator(kWall, forcing(-1.0, 0));
  free_mass.replace(free_mass.find("k = 1.0"), 7, "k = 0.0");
  const Scene free = app::loadScene(written(free_mass));
  try {
    solveStaticContact(free.model, *dogleg, one_step);
    ADD_FAILURE() << "a free mass has no static state";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no contact holds"), std::string::npos) << e.what();
  }
  // Both solvers named when the second fails too, and the first to converge kept.
  auto backup = makeSolver(defaultBackupSolver("dogleg"));
  try {
    solveStaticContact(held.model, {dogleg.get(), backup.get()}, one_step);
    ADD_FAILURE() << "one iteration cannot settle the slipping slider";
  } catch (const StaticSolveFailed& e) {
    EXPECT_NE(std::string(e.what()).find("dogleg: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(backup->name() + ": "), std::string::npos) << e.what();
  }
  const StaticContactState state = solveStaticContact(held.model, {dogleg.get(), backup.get()}, SolverOptions{});
  EXPECT_EQ(state.solver, "dogleg");
  EXPECT_TRUE(state.failed.empty());
  EXPECT_NEAR(state.displacement[0], 1.0, 1e-12);  // slipped: k x = F − μN
}

}  // namespace
}  // namespace eqhb
