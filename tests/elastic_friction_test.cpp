// Elastic dry friction under a varying normal load (ElasticFrictionAft,
// laws/joints/elastic_friction_aft.h): under a constant normal load it is
// penalty-contact + jenkins; in 3D driven along one tangent it is the 2D
// element, rotated in its plane it turns its force; the work of its forces
// over a period is the slider's dissipation; its Jacobian across samples and
// on the assembled systems (full, condensed, dense, sparse) against finite
// differences; and a scene with it solves as the pair of laws it replaces.
#include <gtest/gtest.h>

#include <cmath>

#include "eqhb/app/solve.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/joints/elastic_friction_aft.h"
#include "eqhb/laws/joints/jenkins_aft.h"
#include "eqhb/laws/penalty_contact.h"
#include "eqhb/scenes/law_rho.h"
#include "eqhb/scenes/scene.h"
#include "law_checks.h"
#include "test_support.h"

namespace eqhb {
namespace {

ElasticFrictionAft element(int tangents, double mu = 0.4, double k_t = 2.0, double k_n = 3.0, double gap = -0.5) {
  ElasticFrictionParameters p;
  p.tangents = tangents;
  p.mu = mu;
  p.k_t = k_t;
  p.k_n = k_n;
  p.gap = gap;
  return ElasticFrictionAft(p);
}

// A period of N samples: u_n = n0 + n1 cos(θ + 0.4), u_t1 = a cos θ +
// 0.3 a sin 2θ, u_t2 = b sin θ (columns [n, t1 (, t2)]).
Eigen::MatrixXd path(int n, int tangents, double n0, double n1, double a, double b) {
  Eigen::MatrixXd u(n, 1 + tangents);
  for (int i = 0; i < n; ++i) {
    const double theta = 2 * M_PI * i / n;
    u(i, 0) = n0 + n1 * std::cos(theta + 0.4);
    u(i, 1) = a * std::cos(theta) + 0.3 * a * std::sin(2 * theta);
    if (tangents == 2) u(i, 2) = b * std::sin(theta);
  }
  return u;
}

// The law's samples at λ = 0 (so Ψ = −F[u]), with derivatives or not.
LawSamples evaluated(const Law& law, const Eigen::MatrixXd& u, bool with_derivatives = true) {
  LawSamples s;
  const int n = static_cast<int>(u.rows());
  s.resize(n, law.dimension(), with_derivatives ? law.historyTermsOn(n) : 0);
  s.displacement = u;
  law.evaluate(s, with_derivatives);
  return s;
}

// Samples open (p = 0), slipping (‖T‖ = μp > 0) and sticking.
struct Phases {
  int open = 0, slip = 0, stick = 0;
};
Phases phases(const LawSamples& s, double mu) {
  Phases out;
  for (Eigen::Index i = 0; i < s.psi.rows(); ++i) {
    const double p = -s.psi(i, 0), t = s.psi.row(i).tail(s.psi.cols() - 1).norm();
    if (p == 0.0) ++out.open;
    else if (std::abs(t - mu * p) <= 1e-12 * mu * p) ++out.slip;
    else ++out.stick;
  }
  return out;
}

TEST(ElasticFriction, UnderAConstantNormalLoadIsPenaltyContactPlusJenkins) {
  // u_n ≡ 1.5 past the wall at −0.5: p = 3 · 2 = 6, μp = 2.4 for jenkins.
  const ElasticFrictionAft joint = element(1);
  const PenaltyContact contact(3.0, -0.5);
  const JenkinsAft jenkins({{2.4, 2.0}});
  LawSamples rest;  // a static state where the slider slipped to w = 0.8
  rest.resize(1, 2, 1);
  rest.displacement << 1.5, 2.0;
  LawSamples rest_1d;
  rest_1d.resize(1, 1, 1);
  rest_1d.displacement << 2.0;
  const auto anchored = joint.anchoredAt(rest);
  const auto anchored_jenkins = jenkins.anchoredAt(rest_1d);
  ASSERT_NEAR(static_cast<const ElasticFrictionAft&>(*anchored).anchor().at(0), 0.8, 1e-14);
  struct Case {
    const Law *law, *reference;
    double amplitude;
  };
  // Slipping (amplitude 3), stuck throughout (0.5: the mean convention), and
  // stuck at the static anchor.
  for (const Case& c : {Case{&joint, &jenkins, 3.0}, Case{&joint, &jenkins, 0.5},
                        Case{anchored.get(), anchored_jenkins.get(), 0.5}}) {
    const Eigen::MatrixXd u = path(128, 1, 1.5, 0.0, c.amplitude, 0.0);
    const LawSamples s = evaluated(*c.law, u);
    const LawSamples t = evaluated(*c.reference, u.col(1));
    LawSamples normal;
    normal.resize(128, 1);
    normal.displacement = u.col(0);
    contact.evaluate(normal, false);
    const double scale = t.psi.cwiseAbs().maxCoeff();
    // Forces on the structure: −λ for the element and the contact, +λ for jenkins.
    EXPECT_LT((s.psi.col(0) - normal.psi.col(0)).cwiseAbs().maxCoeff(), 1e-10 * scale) << c.amplitude;
    EXPECT_LT((s.psi.col(1) + t.psi.col(0)).cwiseAbs().maxCoeff(), 1e-10 * scale) << c.amplitude;
    // The tangential block of the Jacobian likewise (Ψ_t = λ − T, Ψ = λ − F, F = −T).
    const Eigen::MatrixXd a = test::sampleJacobian(*c.law, s), b = test::sampleJacobian(*c.reference, t);
    for (int i = 0; i < 128; ++i)
      for (int j = 0; j < 128; ++j) ASSERT_NEAR(a(2 * i + 1, 2 * j + 1), -b(i, j), 1e-10) << i << ", " << j;
  }
}

TEST(ElasticFriction, ThreeDimensionalDrivenAlongOneTangentIsTheTwoDimensional) {
  // The contact opens over part of the period (u_n − g0 = 0.3 ± 0.8).
  const Eigen::MatrixXd u2 = path(96, 1, -0.2, 0.8, 2.0, 0.0), u3 = path(96, 2, -0.2, 0.8, 2.0, 0.0);
  const ElasticFrictionAft plane = element(1), space = element(2);
  const LawSamples a = evaluated(plane, u2), b = evaluated(space, u3);
  const Phases p = phases(a, 0.4);
  EXPECT_GT(p.open, 0);
  EXPECT_GT(p.slip, 0);
  EXPECT_GT(p.stick, 0);
  EXPECT_LT((a.psi - b.psi.leftCols(2)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(b.psi.col(2).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::MatrixXd ja = test::sampleJacobian(plane, a), jb = test::sampleJacobian(space, b);
  for (int i = 0; i < 96; ++i)
    for (int j = 0; j < 96; ++j)
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) ASSERT_NEAR(ja(2 * i + r, 2 * j + c), jb(3 * i + r, 3 * j + c), 1e-12);
}

TEST(ElasticFriction, RotatingTheTangentsInTheirPlaneRotatesTheForce) {
  const ElasticFrictionAft space = element(2);
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  // Always pressed (0.9 ± 0.5) and opening (0.3 ± 0.8), an elliptic slip path.
  for (const double n0 : {0.4, -0.2}) {
    const double n1 = n0 > 0.0 ? 0.5 : 0.8;
    const Eigen::MatrixXd u = path(128, 2, n0, n1, 2.0, 1.3);
    Eigen::MatrixXd turned = u;
    turned.rightCols(2) = u.rightCols(2) * r.transpose();
    const LawSamples a = evaluated(space, u), b = evaluated(space, turned);
    EXPECT_GT(phases(a, 0.4).slip, 0);
    const double scale = a.psi.cwiseAbs().maxCoeff();
    EXPECT_LT((a.psi.col(0) - b.psi.col(0)).cwiseAbs().maxCoeff(), 1e-10 * scale) << n0;
    EXPECT_LT((a.psi.rightCols(2) * r.transpose() - b.psi.rightCols(2)).cwiseAbs().maxCoeff(), 1e-10 * scale) << n0;
  }
}

// The work of the contact forces over the period, ∮ λ · du (trapezoidal),
// and the slider's dissipation Σ μ p_i ‖w_i − w_{i−1}‖ (the radial return's
// force is μp along its step), w = u_t − T/k_t.
struct Energy {
  double work = 0.0, dissipation = 0.0;
};
Energy energy(const Eigen::MatrixXd& u, const LawSamples& s, double mu, double k_t) {
  const int n = static_cast<int>(u.rows()), m = static_cast<int>(u.cols()) - 1;
  const Eigen::MatrixXd lambda = -s.psi;
  const Eigen::MatrixXd w = u.rightCols(m) - lambda.rightCols(m) / k_t;
  Energy e;
  for (int i = 0; i < n; ++i) {
    const int before = (i + n - 1) % n;
    e.work += 0.5 * (lambda.row(i) + lambda.row(before)).dot(u.row(i) - u.row(before));
    e.dissipation += mu * lambda(i, 0) * (w.row(i) - w.row(before)).norm();
  }
  return e;
}

TEST(ElasticFriction, TheWorkOfTheContactForcesIsTheDissipationPerCycle) {
  // Constant load, u_t = X cos θ: the Jenkins loop's area 4 μp (X − μp/k_t).
  const int n = 4096;
  Eigen::MatrixXd u(n, 2);
  for (int i = 0; i < n; ++i) u.row(i) << 1.5, 3.0 * std::cos(2 * M_PI * i / n);
  const Energy loop = energy(u, evaluated(element(1), u, false), 0.4, 2.0);
  const double area = 4 * 2.4 * (3.0 - 2.4 / 2.0);
  EXPECT_NEAR(loop.work, area, 1e-5 * area);
  EXPECT_NEAR(loop.dissipation, area, 1e-5 * area);
  // A varying load that opens, on an elliptic path: the normal force's work
  // over the period vanishes (a spring), the tangential one is dissipated.
  const Eigen::MatrixXd v = path(n, 2, -0.2, 0.8, 2.0, 1.3);
  const Energy varying = energy(v, evaluated(element(2), v, false), 0.4, 2.0);
  EXPECT_GT(varying.dissipation, 0.5);
  EXPECT_NEAR(varying.work, varying.dissipation, 2e-3 * varying.dissipation);
}

// Sample by sample against central differences, on periods that open, slip
// and stick, from the mean and from a static anchor.
TEST(ElasticFriction, JacobianAcrossSamplesMatchesFiniteDifferences) {
  for (int tangents : {1, 2}) {
    const ElasticFrictionAft joint = element(tangents);
    LawSamples rest;
    rest.resize(1, 1 + tangents, 1);
    rest.displacement.row(0).setConstant(1.0);  // slips to its anchor: p = 3.3, T = 2 (1, 1)
    rest.displacement(0, 0) = 0.6;
    const auto anchored = joint.anchoredAt(rest);
    for (const Law* law : {static_cast<const Law*>(&joint), static_cast<const Law*>(anchored.get())})
      for (const double amplitude : {2.0, 0.35, -2.0}) {
        // Negative: always pressed (0.9 ± 0.5), where in 3D the slip
        // directions chain over the whole period.
        const bool pressed = amplitude < 0.0;
        const Eigen::MatrixXd u =
            path(48, tangents, pressed ? 0.4 : -0.2, pressed ? 0.5 : 0.8, std::abs(amplitude), 0.7 * amplitude);
        const LawSamples s = evaluated(*law, u);
        const Phases p = phases(s, 0.4);
        EXPECT_EQ(p.open > 0, !pressed);
        EXPECT_GT(pressed ? p.slip : p.stick + p.slip, 0);
        const Eigen::MatrixXd j = test::sampleJacobian(*law, s);
        const int d = 1 + tangents;
        const double h = 1e-7;
        for (int k = 0; k < 48; ++k)
          for (int b = 0; b < d; ++b) {
            Eigen::MatrixXd plus = u, minus = u;
            plus(k, b) += h;
            minus(k, b) -= h;
            const LawSamples sp = evaluated(*law, plus), sm = evaluated(*law, minus);
            for (int i = 0; i < 48; ++i)
              for (int a = 0; a < d; ++a) {
                const double fd = (sp.psi(i, a) - sm.psi(i, a)) / (2 * h);
                ASSERT_NEAR(j(i * d + a, k * d + b), fd, 1e-6 * (1 + std::abs(fd)))
                    << tangents << " tangent(s), amplitude " << amplitude << ", row (" << i << ", " << a
                    << ") column (" << k << ", " << b << ")";
              }
          }
      }
  }
}

// The full system's sparse Jacobian is its dense one, and the condensed
// system on a sparse factorisation matches finite differences.
TEST(ElasticFriction, SparseJacobiansMatch) {
  for (int tangents : {1, 2}) {
    const auto law = std::make_shared<ElasticFrictionAft>(element(tangents, 0.3, 1.5, 2.5, -0.2));
    const HbModel model = test::lawOnChain(law);
    auto full = makeHbSystem(model, false);
    srand(5);
    const Eigen::VectorXd z = 0.7 * Eigen::VectorXd::Random(full->size());
    Eigen::VectorXd g(full->size()), g_sparse(full->size());
    Eigen::MatrixXd dense(full->size(), full->size());
    ASSERT_TRUE(full->residualAndJacobian(z, g, dense));
    SparseMatrix sparse = full->jacobianPattern();
    ASSERT_TRUE(full->residualAndSparseJacobian(z, g_sparse, sparse));
    EXPECT_LT((Eigen::MatrixXd(sparse) - dense).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
    test::expectJacobianMatchesFiniteDifferences(*makeHbSystem(model, true, LinearAlgebra::kSparse), 5,
                                                 "condensed sparse");
  }
}

// A 2-DOF node against the ground: x tangential (forced at ω), y normal,
// pressed by a constant load 5 on a spring 1 and the penalty spring 3, so
// p = 3 · 5/4 = 3.75 throughout. The element then solves as
// penalty-contact + jenkins (μp = 1.125).
std::string nodeScene(const std::string& laws) {
  return "name = \"node\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0, 0.0], [0.0, 1.0]]\n"
         "stiffness = [[1.0, 0.0], [0.0, 1.0]]\ndamping = [[0.05, 0.0], [0.0, 0.05]]\n"
         "[[forcing]]\ndof = 1\nharmonic = 1\ncos = 1.0\n[[forcing]]\ndof = 2\nharmonic = 0\ncos = 5.0\n" +
         laws + "[harmonic_balance]\nharmonics = 7\nset = \"all\"\nsamples = 64\nomega = 1.2\n";
}

Eigen::VectorXd solved(const std::string& text) {
  app::SceneSettings settings;
  settings.path = "node.toml";
  settings.document = app::SceneSettings::Document{
      [&](const std::vector<std::string>& o) { return parseScene(text, "node.toml", o); },
      [&](const std::vector<std::string>& o) { return lawRhosOfText(text, "node.toml", o); }};
  const app::HbRun run = app::solveHarmonicBalance(settings, app::SolveOptions());
  EXPECT_TRUE(run.result.converged());
  return run.full();
}

TEST(ElasticFriction, ASceneUnderAConstantNormalLoadSolvesAsPenaltyContactPlusJenkins) {
  const Eigen::VectorXd a = solved(nodeScene(
      "[[law]]\ntype = \"elastic-friction\"\ndofs = [2, 1]\nmu = 0.3\nk_t = 2.0\nk_n = 3.0\ngap = 0.0\n"));
  const Eigen::VectorXd b = solved(nodeScene(
      "[[law]]\ntype = \"penalty-contact\"\ndofs = [2]\nstiffness = 3.0\ngap = 0.0\n"
      "[[law]]\ntype = \"jenkins\"\ndofs = [1]\nmuN = 1.125\nk_t = 2.0\n"));
  const int nb = 15;  // harmonics 0..7
  // The displacements, and λ = (p, T) against (p, F = −T).
  EXPECT_LT((a.head(2 * nb) - b.head(2 * nb)).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_NEAR(a[2 * nb], 3.75, 1e-8);
  EXPECT_LT((a.segment(2 * nb, nb) - b.segment(2 * nb, nb)).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT((a.segment(3 * nb, nb) + b.segment(3 * nb, nb)).cwiseAbs().maxCoeff(), 1e-8);
  // The slider slips over the period (else this compares two linear springs).
  EXPECT_GT(b.segment(3 * nb, nb).cwiseAbs().maxCoeff(), 0.5);
}

// Between nodes the components are [normal, tangents]: tangents alone are
// refused rather than read with the first tangent as the normal.
TEST(ElasticFriction, AnElementBetweenNodesNeedsItsNormal) {
  const std::string scene =
      "name = \"pair\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], "
      "[0, 0, 0, 1.0]]\nstiffness = [[2.0, 0, -1.0, 0], [0, 2.0, 0, -1.0], [-1.0, 0, 2.0, 0], [0, -1.0, 0, 2.0]]\n"
      "damping = [[0.1, 0, 0, 0], [0, 0.1, 0, 0], [0, 0, 0.1, 0], [0, 0, 0, 0.1]]\nnode_table = [[1, 2], [3, 4]]\n"
      "[[forcing]]\ndof = 1\ncos = 1.0\n[[law]]\ntype = \"elastic-friction\"\nbetween = [1, 2]\n"
      "tangents = [[1, 0], [0, 1]]\nmu = 0.3\nk_t = 2.0\nk_n = 3.0\n"
      "[harmonic_balance]\nharmonics = 3\nset = \"all\"\nsamples = 64\nomega = 1.0\n";
  try {
    parseScene(scene, "pair.toml");
    ADD_FAILURE() << "an element without its normal was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("law[0].normal = (missing): an elastic-friction element needs its normal"),
              std::string::npos)
        << e.what();
  }
  // On one DOF against the ground there is no tangent.
  std::string grounded = scene;
  grounded.replace(grounded.find("between = [1, 2]\ntangents = [[1, 0], [0, 1]]"), 44, "dofs = [1]");
  try {
    parseScene(grounded, "pair.toml");
    ADD_FAILURE() << "an element on one DOF was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("law[0].dofs = "), std::string::npos) << message;
    EXPECT_NE(message.find("an elastic-friction law acts on [normal, tangential]"), std::string::npos) << message;
  }
  // With its normal, the same element reads [n, t1]: 2 components.
  std::string fixed = scene;
  fixed.replace(fixed.find("tangents = [[1, 0], [0, 1]]"), 27, "normal = [0, 1]\ntangents = [[1, 0]]");
  EXPECT_EQ(parseScene(fixed, "pair.toml").model.laws.at(0).law->dimension(), 2);
}

}  // namespace
}  // namespace eqhb
