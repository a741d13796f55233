// Checks every law must pass (tests/law_registry_test.cpp runs them on every
// example of every registered law): pointwise partials of ψ and the assembled
// weak Jacobians (full and condensed) against central differences.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>
#include <random>
#include <string>

#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/law.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb::test {

// A law built from one example of its registry entry.
struct LawCase {
  std::string label, type;
  std::shared_ptr<Law> law;
};
// Test names and failures show the example's label, not its bytes.
inline void PrintTo(const LawCase& c, std::ostream* out) { *out << c.label; }

// The scene of one registered example: the law on the last DOFs of a 3-DOF
// chain. `extra` lines are added to its table.
inline std::string exampleScene(const LawEntry& entry, const LawExample& example, const std::string& extra = "") {
  std::string dofs;
  for (int a = 0; a < example.dofs; ++a) dofs += (a ? ", " : "") + std::to_string(3 - example.dofs + a + 1);
  return "name = \"" + example.label + "\"\n[structure]\ntype = \"chain\"\ndofs = 3\nm = 1.0\nk = 1.0\nd = 0.05\n"
         "[[law]]\ntype = \"" + entry.type + "\"\ndofs = [" + dofs + "]\n" + example.keys + "\n" + extra +
         "\n[harmonic_balance]\nharmonics = 3\nset = \"all\"\nsamples = 64\nomega = 0.8\n";
}

// Every example of every registered law, built by its parser.
inline std::vector<LawCase> registeredExamples() {
  std::vector<LawCase> cases;
  for (const LawEntry& entry : lawRegistry())
    for (const LawExample& example : entry.examples) {
      const Scene scene = parseScene(exampleScene(entry, example), example.label);
      cases.push_back({example.label, entry.type, scene.model.laws.at(0).law});
    }
  return cases;
}

// Samples of `d` components with displacement, velocity, force and force
// rate drawn uniformly in [-2, 2] (`terms` history terms sized, unset).
inline LawSamples randomSamples(int samples, int d, int terms, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  LawSamples s;
  s.resize(samples, d, terms);
  for (int i = 0; i < samples; ++i)
    for (int a = 0; a < d; ++a) {
      s.displacement(i, a) = u(rng);
      s.velocity(i, a) = u(rng);
      s.force(i, a) = u(rng);
      s.force_rate(i, a) = u(rng);
    }
  return s;
}

// ∂ψ/∂(displacement, velocity, force, force rate), whichever the law uses,
// at `samples` random points in [-2, 2]; the partials are checked column by
// column (a * d + b: component a of ψ, component b of the input).
inline void expectHistoryPartialsMatch(const Law& law, const std::string& label, unsigned seed, int samples);

inline void expectPointwisePartialsMatch(const Law& law, const std::string& label, unsigned seed,
                                         int samples) {
  if (law.historyTerms() > 0) return expectHistoryPartialsMatch(law, label, seed, samples);
  const int d = law.dimension();
  LawSamples s = randomSamples(samples, d, 0, seed);
  law.evaluate(s, true);
  const double h = 1e-7;
  const Eigen::MatrixXd* partials[] = {&s.dpsi_ddisplacement, &s.dpsi_dvelocity, &s.dpsi_dforce,
                                       &s.dpsi_dforce_rate};
  const bool used[] = {law.usesDisplacement(), law.usesVelocity(), true, law.usesForceRate()};
  int checked = 0;
  for (int q = 0; q < 4; ++q) {
    if (!used[q]) continue;
    for (int b = 0; b < d; ++b) {
      LawSamples plus = s, minus = s;
      Eigen::MatrixXd* in_plus[] = {&plus.displacement, &plus.velocity, &plus.force, &plus.force_rate};
      Eigen::MatrixXd* in_minus[] = {&minus.displacement, &minus.velocity, &minus.force, &minus.force_rate};
      in_plus[q]->col(b).array() += h;
      in_minus[q]->col(b).array() -= h;
      law.evaluate(plus, false);
      law.evaluate(minus, false);
      for (int a = 0; a < d; ++a)
        for (int i = 0; i < samples; ++i) {
          const double fd = (plus.psi(i, a) - minus.psi(i, a)) / (2 * h);
          EXPECT_NEAR((*partials[q])(i, a * d + b), fd, 1e-5 * (1 + std::abs(fd)))
              << label << " q=" << q << " a=" << a << " b=" << b << " sample " << i;
          ++checked;
        }
    }
  }
  EXPECT_GT(checked, 0) << label;
}

// ∂Ψ_a(t_i)/∂x_b(t_j) of evaluated samples, assembled: rows i d + a,
// columns j d + b; the pointwise diagonal plus the history terms
// (LawSamples), a term on the period's mean spread over every sample.
inline Eigen::MatrixXd sampleJacobian(const Law& law, const LawSamples& s) {
  const int n = static_cast<int>(s.psi.rows()), d = law.dimension(), terms = law.historyTermsOn(n);
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(n * d, n * d);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) {
        const int ab = a * d + b;
        j(i * d + a, i * d + b) += s.dpsi_ddisplacement(i, ab);
        for (int k = 0; k < terms; ++k) {
          const double w = s.history_weight(i, ab * terms + k);
          const int sample = s.history_sample(i, ab * terms + k);
          if (w == 0.0) continue;
          if (sample == LawSamples::kPeriodMean)
            for (int m = 0; m < n; ++m) j(i * d + a, m * d + b) += w / n;
          else
            j(i * d + a, sample * d + b) += w;
        }
      }
  return j;
}

// A history law (Law::historyTerms): Ψ over all samples against central
// differences in the displacement of each sample in turn, at random inputs
// in [-2, 2] read as one period. Its Jacobian is ∂Ψ/∂λ = dpsi_dforce
// pointwise, and across samples the diagonal plus the history terms
// (LawSamples). Each column of the displacement Jacobian is checked whole.
inline void expectHistoryPartialsMatch(const Law& law, const std::string& label, unsigned seed, int samples) {
  const int d = law.dimension(), terms = law.historyTermsOn(samples);
  LawSamples s = randomSamples(samples, d, terms, seed);
  law.evaluate(s, true);
  const Eigen::MatrixXd jacobian = sampleJacobian(law, s);
  const double h = 1e-7;
  int checked = 0;
  // The inputs alone: the differences need no Jacobian (a law whose terms
  // grow with the period has d² N² of them).
  LawSamples inputs;
  inputs.resize(samples, d);
  inputs.displacement = s.displacement;
  inputs.velocity = s.velocity;
  inputs.force = s.force;
  inputs.force_rate = s.force_rate;
  for (int j = 0; j < samples; ++j)
    for (int b = 0; b < d; ++b) {
      LawSamples plus = inputs, minus = inputs;
      plus.displacement(j, b) += h;
      minus.displacement(j, b) -= h;
      law.evaluate(plus, false);
      law.evaluate(minus, false);
      for (int i = 0; i < samples; ++i)
        for (int a = 0; a < d; ++a) {
          const double fd = (plus.psi(i, a) - minus.psi(i, a)) / (2 * h);
          ASSERT_NEAR(jacobian(i * d + a, j * d + b), fd, 1e-5 * (1 + std::abs(fd)))
              << label << " row (" << i << ", " << a << ") column (" << j << ", " << b << ")";
          ++checked;
        }
    }
  for (int b = 0; b < d; ++b) {  // ∂Ψ/∂λ, pointwise
    LawSamples plus = inputs, minus = inputs;
    plus.force.col(b).array() += h;
    minus.force.col(b).array() -= h;
    law.evaluate(plus, false);
    law.evaluate(minus, false);
    for (int i = 0; i < samples; ++i)
      for (int a = 0; a < d; ++a)
        EXPECT_NEAR(s.dpsi_dforce(i, a * d + b), (plus.psi(i, a) - minus.psi(i, a)) / (2 * h), 1e-6) << label;
  }
  // Not all zero: some sample's force reads another sample's displacement.
  EXPECT_GT((jacobian - Eigen::MatrixXd(jacobian.diagonal().asDiagonal())).cwiseAbs().maxCoeff(), 0.0) << label;
  EXPECT_GT(checked, 0) << label;
}

// The assembled Jacobian at a random z (srand(seed), entries in ±0.7)
// against central differences, to 1e-5 of its size.
inline void expectJacobianMatchesFiniteDifferences(HbSystem& system, unsigned seed, const std::string& label) {
  srand(seed);
  const Eigen::VectorXd z = 0.7 * Eigen::VectorXd::Random(system.size());
  Eigen::VectorXd g(system.size());
  Eigen::MatrixXd j(system.size(), system.size());
  ASSERT_TRUE(system.residualAndJacobian(z, g, j)) << label;
  const Eigen::MatrixXd fd = finiteDifferenceJacobian(system, z);
  EXPECT_LT((j - fd).cwiseAbs().maxCoeff(), 1e-5 * (1.0 + fd.cwiseAbs().maxCoeff())) << label;
}

// The law on the last DOFs of a 3-DOF chain, forced at DOF 1, all
// harmonics 0..3 on 64 samples, at ω = 0.8.
inline HbModel lawOnChain(const std::shared_ptr<Law>& law) {
  HbModel model;
  const int n = 3;
  Eigen::MatrixXd k = 2.0 * Eigen::MatrixXd::Identity(n, n);
  k(0, 1) = k(1, 0) = -1.0;
  model.structure = LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd::Identity(n, n), k, 0.05 * k);
  model.structure.loads.push_back({0, 1, 2.0, 0.5});
  const int d = law->dimension();
  std::vector<int> dofs;
  for (int a = 0; a < d; ++a) dofs.push_back(n - d + a);
  model.laws.push_back({dofs, law});
  model.basis = HarmonicSet(HarmonicKind::kAll, 3);
  model.samples = 64;
  model.omega = 0.8;
  return model;
}

// lawOnChain at a random z: the weak Jacobian of the full and of the
// condensed system.
inline void expectAssembledJacobiansMatch(const std::shared_ptr<Law>& law, const std::string& label,
                                          unsigned seed) {
  const HbModel model = lawOnChain(law);
  for (bool condensed : {false, true}) {
    expectJacobianMatchesFiniteDifferences(*makeHbSystem(model, condensed), seed,
                                           label + (condensed ? " condensed" : " full"));
  }
}

// The law between the last d DOFs of a 3-DOF chain (node p) and d more DOFs
// (node q) held to the ground by springs of stiffness `held`, along a rotated
// frame R (u = R (x_p − x_q)): the structure's 3 + d DOFs.
inline HbModel lawBetweenNodes(const std::shared_ptr<Law>& law, double held, const Eigen::MatrixXd& frame) {
  const int n = 3, d = law->dimension();
  HbModel model;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n + d, n + d);
  k.topLeftCorner(n, n) = 2.0 * Eigen::MatrixXd::Identity(n, n);
  k(0, 1) = k(1, 0) = -1.0;
  Eigen::MatrixXd c = 0.05 * k;
  for (int a = 0; a < d; ++a) k(n + a, n + a) = held;
  model.structure = LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd::Identity(n + d, n + d), k, c);
  model.structure.loads.push_back({0, 1, 2.0, 0.5});
  std::vector<int> p, q;
  std::vector<Eigen::VectorXd> directions;
  for (int a = 0; a < d; ++a) {
    p.push_back(n - d + a);
    q.push_back(n + a);
    directions.push_back(frame.row(a).transpose());
  }
  model.laws.push_back({LawAttachment::relative(p, q, directions), law});
  model.basis = HarmonicSet(HarmonicKind::kAll, 3);
  model.samples = 64;
  model.omega = 0.8;
  return model;
}

// Between two nodes: the assembled Jacobians (full and condensed) against
// central differences on a rotated frame, and, with the second node held
// 5e11 times stiffer than the chain along the axes, the condensed residual of
// the grounded law at the same forces, up to the held node's own motion
// (5e11: stiffer is refused by the condensation's rcond check).
inline void expectBetweenNodesMatches(const std::shared_ptr<Law>& law, const std::string& label, unsigned seed) {
  const int d = law->dimension();
  const Eigen::MatrixXd frame =
      Eigen::Matrix3d(Eigen::AngleAxisd(0.6, Eigen::Vector3d(1.0, 2.0, 0.5).normalized())).topLeftCorner(d, d);
  Eigen::MatrixXd orthonormal = Eigen::HouseholderQR<Eigen::MatrixXd>(frame).householderQ();
  for (bool condensed : {false, true}) {
    expectJacobianMatchesFiniteDifferences(*makeHbSystem(lawBetweenNodes(law, 3.0, orthonormal), condensed), seed,
                                           label + " between nodes" + (condensed ? " condensed" : " full"));
  }
  HbModel grounded = lawBetweenNodes(law, 5e11, Eigen::MatrixXd::Identity(d, d));
  const HbModel held = grounded;
  grounded.structure =
      LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd(held.structure.mass).topLeftCorner(3, 3),
                                                Eigen::MatrixXd(held.structure.stiffness).topLeftCorner(3, 3),
                                                Eigen::MatrixXd(held.structure.damping).topLeftCorner(3, 3));
  grounded.structure.loads = held.structure.loads;
  std::vector<int> dofs;
  for (int a = 0; a < d; ++a) dofs.push_back(3 - d + a);
  grounded.laws[0].attachment = LawAttachment(dofs);
  CondensedSystem a(grounded), b(held);
  srand(seed);
  const Eigen::VectorXd z = 0.7 * Eigen::VectorXd::Random(a.size());
  Eigen::VectorXd ga(a.size()), gb(b.size());
  Eigen::MatrixXd ja(a.size(), a.size());
  ASSERT_TRUE(a.residualAndJacobian(z, ga, ja));
  ASSERT_TRUE(b.residual(z, gb));
  // The held node still moves by |λ| / 5e11, and the law's displacement
  // with it: Ψ changes by up to |∂Ψ/∂x| times that. The condensed Jacobian's
  // entries are ∂Ψ/∂x times the chain's compliances (>= 1/3, its stiffest
  // mode being 3) plus ∂Ψ/∂λ, so 3 max|J| bounds |∂Ψ/∂x|.
  const double held_motion = z.cwiseAbs().maxCoeff() / 5e11;
  const double bound = 1e-12 * (1.0 + ga.cwiseAbs().maxCoeff()) + 3.0 * ja.cwiseAbs().maxCoeff() * held_motion;
  EXPECT_LT((ga - gb).cwiseAbs().maxCoeff(), bound) << label << " held node";
}

}  // namespace eqhb::test
