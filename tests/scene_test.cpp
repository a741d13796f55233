#include "eqhb/scenes/scene.h"
#include "eqhb/scenes/law_rho.h"

#include <gtest/gtest.h>

#include <cmath>

#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/invariants.h"
#include "check_support.h"

namespace eqhb {
namespace {

const char* kValid = R"(
name = "t"
[structure]
type = "chain"
m = 1.0
k = 1.0
d = 0.02
[[forcing]]
dof = 1
cos = 20.0
[[law]]
type = "coulomb-1d"
dofs = [2]
muN = 7.2
[harmonic_balance]
harmonics = 10
samples = 64
omega = 0.4
)";

// The valid scene with its first `from` replaced by `to`.
std::string replaced(const std::string& from, const std::string& to) { return test::replaced(kValid, from, to); }

void expectError(const std::string& text, const std::string& needle,
                 const std::vector<std::string>& overrides = {}) {
  test::expectSceneError(text, needle, overrides);
}

TEST(Scene, TheShippedFriction1dSceneHasTheSpecParameters) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"));
  const HbModel& m = scene.model;
  EXPECT_EQ(scene.name, "friction-1d");
  EXPECT_EQ(m.structure.dofs(), 2);
  EXPECT_DOUBLE_EQ(m.structure.stiffness.coeff(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(m.structure.stiffness.coeff(1, 1), 1.0);
  EXPECT_DOUBLE_EQ(m.structure.damping.coeff(0, 1), -0.02);
  ASSERT_EQ(m.laws.size(), 1u);
  EXPECT_EQ(m.laws[0].attachment.dofs(), std::vector<int>{1});
  EXPECT_TRUE(m.laws[0].attachment.grounded());
  const auto& law = dynamic_cast<const Coulomb1D&>(*m.laws[0].law);
  EXPECT_DOUBLE_EQ(law.muN(), 7.2);
  EXPECT_EQ(law.form(), CoulombForm::kMinMax);
  EXPECT_EQ(m.basis.count(), 10);
  EXPECT_EQ(m.basis.highest(), 19);
  EXPECT_EQ(m.samples, 1024);
  EXPECT_DOUBLE_EQ(m.omega, 0.4);
  EXPECT_DOUBLE_EQ(*scene.sweep_from, 0.1);
  EXPECT_DOUBLE_EQ(*scene.sweep_to, 0.8);
}

TEST(Scene, OverridesChangeAnyValueBeforeValidation) {
  const Scene scene = parseScene(kValid, "scene.toml",
                                 {"law[0].muN=3.5", "law.form=projection", "structure.d=0.1",
                                  "harmonic_balance.omega=0.7"});
  const auto& law = dynamic_cast<const Coulomb1D&>(*scene.model.laws[0].law);
  EXPECT_DOUBLE_EQ(law.muN(), 3.5);
  EXPECT_EQ(law.form(), CoulombForm::kProjection);
  EXPECT_DOUBLE_EQ(scene.model.structure.damping.coeff(1, 1), 0.1);
  EXPECT_DOUBLE_EQ(scene.model.omega, 0.7);
  expectError(kValid, "law[0].muN = -1", {"law[0].muN=-1"});
  expectError(kValid, "index 3 out of range", {"law[3].muN=1"});
  expectError(kValid, "must be PATH=VALUE", {"muN"});
}

TEST(Scene, MalformedOrIncompleteFilesNameTheProblem) {
  expectError("name = \"t\"\n[structure\n", "malformed scene file");
  expectError(replaced("[harmonic_balance]", "[harmonic_balanse]"), "harmonic_balance = (missing): required");
  expectError(replaced("muN = 7.2", "mu = 7.2"), "law[0].muN = (missing): required");
  expectError(replaced("d = 0.02", "d = 0.02\ndamping_ratio = 1"), "structure.damping_ratio = 1: unknown key");
  expectError(replaced("muN = 7.2", "muN = \"lots\""), "law[0].muN = \"lots\": must be a number");
}

TEST(Scene, NonPhysicalValuesAreRejected) {
  expectError(replaced("m = 1.0", "m = 0.0"), "structure.m = 0: mass must be > 0");
  expectError(replaced("m = 1.0", "m = -2.0"), "structure.m = -2: mass must be > 0");
  expectError(replaced("muN = 7.2", "muN = -1.0"), "law[0].muN = -1: friction limit must be >= 0");
  expectError(replaced("muN = 7.2", "muN = 7.2\nrho = 0.0"), "law[0].rho = 0: must be > 0");
  expectError(replaced("muN = 7.2", "muN = nan"), "law[0].muN = nan: must be finite");
  expectError(replaced("omega = 0.4", "omega = inf"), "harmonic_balance.omega = inf: must be finite");
  expectError(replaced("samples = 64", "samples = 38"),
              "harmonic_balance.samples = 38: must be >= 2 k_max + 1 = 39");
  expectError(replaced("dofs = [2]", "dofs = [3]"), "law[0].dofs = 3: no such DOF");
  expectError(replaced("dofs = [2]", "dofs = [1, 2]"), "acts on exactly 1 DOF");
  expectError(replaced("cos = 20.0", "cos = 20.0\nharmonic = 2"), "forcing[0].harmonic = 2: not in the odd");
  expectError(replaced("type = \"coulomb-1d\"", "type = \"coulomb-3d\""), "unknown law");
}

TEST(Scene, LawsOfEveryTypeAreValidated) {
  auto law = [](const std::string& body) {
    return replaced("type = \"coulomb-1d\"\ndofs = [2]\nmuN = 7.2", body);
  };
  expectError(law("type = \"coulomb-2d\"\ndofs = [2]\nmuN = 8.0"), "acts on exactly 2 DOF(s)");
  expectError(law("type = \"coulomb-2d\"\ndofs = [1, 2]\nmuN = -8.0"), "law[0].muN = -8: friction limit must be >= 0");
  expectError(law("type = \"coulomb-2d\"\ndofs = [1, 2]\nmuN = 8.0\nform = \"minmax\""),
              "law[0].form = \"minmax\": a coulomb-2d law has forms max, projection, smoothed, tanh");
  expectError(law("type = \"signorini\"\ndofs = [2]\ngap = nan"), "law[0].gap = nan: must be finite");
  expectError(law("type = \"signorini\"\ndofs = [3]\ngap = 1.0"), "law[0].dofs = 3: no such DOF");
  expectError(law("type = \"stribeck\"\ndofs = [2]\nmuN_dynamic = -1.0\nmuN_static = 1.5\nv_s = 0.5"),
              "law[0].muN_dynamic = -1: friction limit must be >= 0");
  expectError(law("type = \"stribeck\"\ndofs = [2]\nmuN_dynamic = 1.0\nmuN_static = 0.5\nv_s = 0.5"),
              "law[0].muN_static = 0.5: must be >= muN_dynamic = 1");
  expectError(law("type = \"stribeck\"\ndofs = [2]\nmuN_dynamic = 1.0\nmuN_static = 1.5\nv_s = 0.0"),
              "law[0].v_s = 0: must be > 0");
  expectError(law("type = \"cubic\"\ndofs = [2]\nepsilon = inf"), "law[0].epsilon = inf: must be finite");
  expectError(law("type = \"cubic\"\ndofs = [2]\nepsilon = 1.0\nrho = 2.0"), "law[0].rho = 2.0: unknown key");
}

TEST(Scene, TimeReferenceDefaultsAreReadAndValidated) {
  const Scene plain = parseScene(kValid, "scene.toml");
  EXPECT_FALSE(plain.time_reference.step || plain.time_reference.theta || plain.time_reference.periods ||
               plain.time_reference.periodic_tolerance);
  const Scene own = parseScene(std::string(kValid) + "[time_reference]\nstep = 1e-3\ntheta = 0.55\nperiods = 300\n"
                                                     "periodic_tolerance = 1e-8\n",
                               "scene.toml");
  EXPECT_EQ(*own.time_reference.step, 1e-3);
  EXPECT_EQ(*own.time_reference.theta, 0.55);
  EXPECT_EQ(*own.time_reference.periods, 300);
  EXPECT_EQ(*own.time_reference.periodic_tolerance, 1e-8);
  const std::string section = std::string(kValid) + "[time_reference]\n";
  expectError(section + "theta = 0.4\n", "scene.toml: time_reference.theta = 0.4: must be in [0.5, 1]");
  expectError(section + "step = 0\n", "time_reference.step = 0: must be > 0");
  expectError(section + "step = nan\n", "time_reference.step = nan: must be finite");
  expectError(section + "periods = 0\n", "time_reference.periods = 0: must be >= 1");
  expectError(section + "periods = 4294967306\n", "time_reference.periods = 4294967306: must be <=");
  expectError(section + "periodic_tolerance = -1\n", "time_reference.periodic_tolerance = -1: must be > 0");
  expectError(section + "h = 1e-3\n", "time_reference.h = 0.001: unknown key (allowed here: periodic_tolerance, "
                                       "periods, step, theta)");
}

TEST(Scene, NumbersOutOfTheDoubleRangeAreRefusedNotRounded) {
  // toml11 reads 1e-400 as 0 and 1e400 as the largest double, silently.
  expectError(replaced("muN = 7.2", "muN = 1e-400"),
              "scene.toml: law[0].muN = 1e-400: underflows to 0; not representable");
  expectError(replaced("muN = 7.2", "muN = 1e400"), "law[0].muN = 1e400: overflows; not representable");
  expectError(replaced("omega = 0.4", "omega = -1_0e-4_00"), "harmonic_balance.omega = -1_0e-4_00: underflows to 0");
  expectError(kValid, "law[0].muN = 1e-400: underflows to 0", {"law[0].muN=1e-400"});
  expectError(replaced("type = \"chain\"\nm = 1.0\nk = 1.0\nd = 0.02",
                       "type = \"matrices\"\nmass = [[1, 0], [0, 1]]\ndamping = [[0, 0], [0, 0]]\n"
                       "stiffness = [[2, -1], [-1, 2e-999]]"),
              "structure.stiffness[1][1] = 2e-999: underflows to 0");
  // Small but representable values (subnormal included) and an exact 0 stay.
  EXPECT_EQ(parseScene(replaced("muN = 7.2", "muN = 5e-320"), "s").model.laws.size(), 1u);
  EXPECT_EQ(parseScene(replaced("muN = 7.2", "muN = 0.0e-999"), "s").model.laws.size(), 1u);
}

TEST(Scene, ANulInsideAStringIsRefused) {
  // Opened as a file name, "m.mtx\0.txt" would be "m.mtx".
  expectError(replaced("type = \"chain\"\nm = 1.0\nk = 1.0\nd = 0.02",
                       "type = \"matrix-market\"\nmass = \"m.mtx\\u0000.txt\"\nstiffness = \"k.mtx\""),
              "scene.toml: structure.mass = \"m.mtx");
  expectError(replaced("type = \"chain\"\nm = 1.0\nk = 1.0\nd = 0.02",
                       "type = \"matrix-market\"\nmass = \"m.mtx\\u0000.txt\"\nstiffness = \"k.mtx\""),
              "must not contain a NUL character");
}

TEST(Scene, AnUnknownLawKeyListsTheKeysThatLawAllows) {
  // A typo of an optional key: the list holds the keys allowed, not only those present.
  expectError(replaced("muN = 7.2", "muN = 7.2\nrh0 = 2"),
              "law[0].rh0 = 2: unknown key (allowed here: beta, between, dofs, form, formulation, muN, nodes, rho, rho_factor, type)");
  expectError(replaced("type = \"coulomb-1d\"\ndofs = [2]\nmuN = 7.2",
                       "type = \"cubic\"\ndofs = [2]\nepsilon = 1\nrho = 1"),
              "law[0].rho = 1: unknown key (allowed here: between, dofs, epsilon, formulation, nodes, type)");
}

TEST(Scene, EveryShippedSceneLoads) {
  for (const char* file : {"friction-1d.toml", "friction-2d.toml", "friction-2d-sliding.toml", "contact.toml",
                           "stribeck.toml", "cubic.toml"})
    EXPECT_NO_THROW(loadScene(test::problem(file))) << file;
}

TEST(Scene, MissingFileIsAnInputError) {
  EXPECT_THROW(loadScene("/nonexistent/scene.toml"), InputError);
}

TEST(Scene, ADirectoryIsNotAScene) {
  try {
    loadScene(EQHB_PROBLEMS_DIR);
    FAIL() << "a directory was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
}

TEST(Scene, InvalidUtf8IsRefusedBeforeParsing) {
  // A literal string with a stray byte: the parser read past its buffer.
  expectError("a = 'x\xff'\n", "line 1: not valid UTF-8");
  expectError(replaced("name = \"t\"", "name = \"t\"\ndescription = \"\xc0\x80\""), "line 3: not valid UTF-8");
  expectError(replaced("name = \"t\"", "# \xed\xa0\x80"), "not valid UTF-8");     // a surrogate
  expectError(replaced("name = \"t\"", "# \xf4\x90\x80\x80"), "not valid UTF-8");  // above U+10FFFF
  expectError(replaced("name = \"t\"", "# \xe2\x82"), "not valid UTF-8");          // cut short
  // Well-formed UTF-8 of every length still loads.
  const Scene scene = parseScene(replaced("name = \"t\"", "name = 'ω ≥ 0 – \xf0\x9f\x99\x82'"), "scene.toml");
  EXPECT_EQ(scene.name, "ω ≥ 0 – \xf0\x9f\x99\x82");
}

TEST(Scene, DeepNestingIsRefusedBeforeParsing) {
  const int deep = 10000;
  expectError("a = " + std::string(deep, '[') + std::string(deep, ']') + "\n", "nested deeper than");
  std::string tables = "a = ";
  for (int i = 0; i < deep; ++i) tables += "{b=";
  tables += "1" + std::string(deep, '}') + "\n";
  expectError(tables, "nested deeper than");
  expectError(kValid, "--set: line 1: arrays or inline tables nested deeper than",
              {"law.muN=" + std::string(deep, '[') + std::string(deep, ']')});
  // Brackets inside strings and comments are text, not nesting.
  const std::string brackets(100, '[');
  EXPECT_NO_THROW(parseScene(replaced("name = \"t\"", "name = \"t\"\ndescription = '" + brackets + "' # " + brackets),
                             "scene.toml"));
  EXPECT_NO_THROW(parseScene(replaced("name = \"t\"", "name = \"t\"\ndescription = \"\"\"\n" + brackets + "\\\"\n\"\"\""),
                             "scene.toml"));
}

TEST(Scene, OversizedTextIsRefused) {
  std::string text = kValid;
  text += std::string(16u << 20, '#');
  expectError(text, "a scene file is at most");
}

TEST(Scene, IntegersAreRangeCheckedBeforeNarrowing) {
  // 4294967306 = 2^32 + 10 used to become 10.
  expectError(replaced("harmonics = 10", "harmonics = 4294967306"),
              "harmonic_balance.harmonics = 4294967306: must be <= 1048576");
  expectError(replaced("harmonics = 10", "harmonics = 2147483647"),
              "harmonic_balance.harmonics = 2147483647: must be <= 1048576");
  expectError(replaced("samples = 64", "samples = 4294967360"), "harmonic_balance.samples = 4294967360: must be <=");
  expectError(replaced("samples = 64", "samples = 100000000"), "harmonic_balance.samples = 100000000: must be <=");
  expectError(replaced("d = 0.02", "d = 0.02\ndofs = 4294967298"), "structure.dofs = 4294967298: must be <=");
  expectError(replaced("dof = 1", "dof = 4294967297"), "forcing[0].dof = 4294967297: must be <=");
  expectError(replaced("cos = 20.0", "cos = 20.0\nharmonic = 4294967297"), "forcing[0].harmonic = 4294967297: must be <=");
  expectError(replaced("dofs = [2]", "dofs = [4294967298]"), "law[0].dofs = 4294967298: no such DOF");
  expectError(replaced("harmonics = 10", "harmonics = -9223372036854775808"), "harmonic_balance.harmonics = -9223372036854775808");
}

TEST(Scene, SizesAreBoundedByTheMemoryTheyImply) {
  // A 100,000-DOF chain is sparse (a few MB; 224 GiB as dense M, C, K): it loads.
  const Scene chain = parseScene(replaced("d = 0.02", "d = 0.02\ndofs = 100000"), "s.toml");
  EXPECT_EQ(chain.model.structure.dofs(), 100000);
  expectError(replaced("d = 0.02", "d = 0.02\ndofs = 2147483647"),
              "structure.dofs = 2147483647: a chain's sparse M, C and K needs about");
  // H = 100000: the law's nb x nb Jacobian blocks alone need 640 GB.
  expectError(replaced("harmonics = 10\nsamples = 64", "harmonics = 100000\nsamples = 400000"),
              "harmonics = 100000: the model (2 DOFs, 1 law components, 200000 coefficients and 400000 samples");
  // A large but affordable basis still loads.
  EXPECT_NO_THROW(parseScene(replaced("harmonics = 10\nsamples = 64", "harmonics = 2000\nsamples = 8192"), "s.toml"));
}

TEST(Scene, MatricesFollowTheChainRules) {
  const std::string matrices = R"(
name = "m"
[structure]
type = "matrices"
mass = [[1.0, 0.0], [0.0, 1.0]]
damping = [[0.1, 0.0], [0.0, 0.1]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
[[forcing]]
dof = 1
cos = 1.0
[harmonic_balance]
harmonics = 3
samples = 64
omega = 1.0
)";
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = matrices;
    return text.replace(text.find(from), from.size(), to);
  };
  EXPECT_NO_THROW(parseScene(matrices, "m.toml"));
  expectError(with("[[2.0, -1.0], [-1.0, 1.0]]", "[[-1.0, 0.0], [0.0, 1.0]]"),
              "structure.stiffness: must be positive semidefinite");
  expectError(with("[[2.0, -1.0], [-1.0, 1.0]]", "[[1.0, -2.0], [-2.0, 1.0]]"),
              "structure.stiffness: must be positive semidefinite (it has a negative direction");
  expectError(with("[[0.1, 0.0], [0.0, 0.1]]", "[[0.1, 0.0], [0.0, -0.5]]"),
              "structure.damping: must be positive semidefinite");
  // The chain's own matrices pass the same rule (k = 0, d = 0 included).
  EXPECT_NO_THROW(parseScene(replaced("k = 1.0\nd = 0.02", "k = 0.0\nd = 0.0"), "scene.toml"));
}

}  // namespace
}  // namespace eqhb

namespace eqhb {
namespace {

// The ρ of each law, as the file and its overrides set it (what --accuracy scales).
TEST(Scene, LawRhosFollowTheFileAndItsOverrides) {
  const auto large = lawRhos(test::problem("beam-joint-large.toml"));
  ASSERT_GE(large.size(), 3u);
  EXPECT_DOUBLE_EQ(large[0]->value, 1.13e-09);
  EXPECT_DOUBLE_EQ(large[1]->value, 9.07e-09);
  EXPECT_DOUBLE_EQ(large[2]->value, 3.06e-08);
  EXPECT_FALSE(large[0]->scale_free);
  const auto friction = lawRhos(test::problem("friction-1d.toml"), {"law[0].rho=0.25"});
  ASSERT_EQ(friction.size(), 1u);
  EXPECT_DOUBLE_EQ(friction[0]->value, 0.25);
  const auto cubic = lawRhos(test::problem("cubic.toml"));
  ASSERT_EQ(cubic.size(), 1u);
  EXPECT_FALSE(cubic[0].has_value()) << "a cubic spring has no rho";
  const auto cantilever = lawRhos(test::problem("cantilever-friction-si.toml"));  // rho not given: scale-free
  ASSERT_EQ(cantilever.size(), 1u);
  EXPECT_TRUE(cantilever[0]->scale_free);
  EXPECT_EQ(cantilever[0]->factor, 1.0);
  const auto damper = lawRhos(test::problem("damper.toml"));  // contact-friction, rho = 1 given
  ASSERT_FALSE(damper.empty());
  for (const auto& r : damper) EXPECT_FALSE(r->scale_free);
  const auto scaled = lawRhos(test::problem("cantilever-friction-si.toml"), {"law[0].rho_factor=0.1"});
  EXPECT_EQ(scaled[0]->factor, 0.1);
  EXPECT_EQ(scaledRhoOverride(0, *scaled[0], 0.1), "law[0].rho_factor=0.01");
  EXPECT_THROW(lawRhos(test::problem("friction-1d.toml"), {"law[0].rho=-1"}), InputError);
}

TEST(Scene, TwoLawsOnOneStructure) {
  // Friction on DOF 2 and a cubic spring on DOF 1 of the same chain.
  const std::string text =
      replaced("[harmonic_balance]", "[[law]]\ntype = \"cubic\"\ndofs = [1]\nepsilon = 0.002\n[harmonic_balance]");
  const Scene scene = parseScene(text, "two-laws.toml", {"harmonic_balance.samples=512"});
  ASSERT_EQ(scene.model.laws.size(), 2u);
  for (bool condensed : {true, false}) {
    std::unique_ptr<HbSystem> system;
    if (condensed) system = std::make_unique<CondensedSystem>(scene.model);
    else system = std::make_unique<FullSystem>(scene.model);
    srand(2);
    const Eigen::VectorXd z = Eigen::VectorXd::Random(system->size());
    EXPECT_LT(test::jacobianError(*system, z), 1e-5);
    const SolverResult r = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
    ASSERT_TRUE(r.converged()) << (condensed ? "condensed " : "full ") << r.summary();
    const auto reports = checkInvariants(scene.model, system->fullCoefficients(r.solution));
    ASSERT_EQ(reports.size(), 2u);
    EXPECT_EQ(reports[1].type, "cubic");
    EXPECT_LT(reports[0].violations[0].second, 0.1);  // friction limit
  }
}

}  // namespace
}  // namespace eqhb
