#include "eqhb/modes/linear_modes.h"

#include <cmath>
#include <stdexcept>


namespace eqhb {

namespace {
// The partials (a, b, c, e) of component `a` of `law` at rest: at zero, or
// on `rest`, the law's inputs in a static state (one sample).
struct RestPartials {
  double displacement = 0.0, velocity = 0.0, force = 0.0, force_rate = 0.0;
};

RestPartials partialsAtRest(const Law& law, int component, const LawSamples* rest) {
  const int d = law.dimension();
  LawSamples samples;
  if (rest)
    samples = *rest;
  else
    samples.resize(1, d, law.historyTerms());
  law.evaluate(samples, true);
  const int ab = component * d + component;
  RestPartials p;
  if (law.usesDisplacement()) p.displacement = samples.dpsi_ddisplacement(0, ab);
  if (law.usesVelocity()) p.velocity = samples.dpsi_dvelocity(0, ab);
  p.force = samples.dpsi_dforce(0, ab);
  if (law.usesForceRate()) p.force_rate = samples.dpsi_dforce_rate(0, ab);
  return p;
}
// Component a reads one DOF as it is (the grounded form): its force is that
// DOF's, and held it holds that DOF.
bool onOneDof(const LawAttachment& attachment, int a) {
  return attachment.row(a).size() == 1 && attachment.row(a).front().weight == 1.0;
}
}  // namespace

LinearisedStructure linearisedStructure(const HbModel& model, const StaticContactState* at_rest) {
  const LinearStructure& s = model.structure;
  const int n = s.dofs();
  LinearisedStructure out;
  out.stiffness = Eigen::MatrixXd(s.stiffness);
  out.damping = Eigen::MatrixXd(s.damping);
  out.held.assign(n, false);
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const AttachedLaw& attached = model.laws[l];
    const Law& law = *attached.law;
    for (int a = 0; a < law.dimension(); ++a) {
      const RestPartials p = partialsAtRest(law, a, at_rest ? &at_rest->rest[l] : nullptr);
      const double sign = law.forceSign();
      const Eigen::VectorXd w = attached.attachment.transposeDense(n).col(a);
      if (p.force != 0.0) {
        out.stiffness += (sign * p.displacement / p.force) * w * w.transpose();
        out.damping += (sign * p.velocity / p.force) * w * w.transpose();
      } else if (p.force_rate != 0.0) {
        out.stiffness += (sign * p.velocity / p.force_rate) * w * w.transpose();
      } else if (p.displacement != 0.0 || p.velocity != 0.0) {
        if (onOneDof(attached.attachment, a))
          out.held[attached.attachment.dof(a)] = true;
        else
          out.ties.push_back(w);
      }
    }
  }
  return out;
}

std::vector<LinearMode> linearModes(const HbModel& model, const StaticContactState* at_rest) {
  const LinearisedStructure lin = linearisedStructure(model, at_rest);
  const Eigen::MatrixXd mass(model.structure.mass);
  const int n = model.structure.dofs();
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (!lin.held[i]) free.push_back(i);
  std::vector<LinearMode> modes;
  if (free.empty()) return modes;
  // The motions the ties allow: x_free = N y, N an orthonormal basis of the
  // null space of the ties (restricted to the free DOFs).
  const int f = static_cast<int>(free.size());
  Eigen::MatrixXd basis = Eigen::MatrixXd::Identity(f, f);
  if (!lin.ties.empty()) {
    Eigen::MatrixXd ties(lin.ties.size(), f);
    for (size_t t = 0; t < lin.ties.size(); ++t)
      for (int r = 0; r < f; ++r) ties(t, r) = lin.ties[t][free[r]];
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(ties.transpose());
    const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(f, f);
    basis = q.rightCols(f - qr.rank());
  }
  const int m = static_cast<int>(basis.cols());
  if (m == 0) return modes;
  Eigen::MatrixXd k_free(f, f), m_free(f, f);
  for (int r = 0; r < f; ++r)
    for (int c = 0; c < f; ++c) {
      k_free(r, c) = lin.stiffness(free[r], free[c]);
      m_free(r, c) = mass(free[r], free[c]);
    }
  const Eigen::MatrixXd k = basis.transpose() * k_free * basis, mm = basis.transpose() * m_free * basis;
  // Symmetrised: the laws' springs are w wᵀ, K and M symmetric.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (k + k.transpose()), mm);
  if (eigen.info() != Eigen::Success)
    throw std::runtime_error("linear modes: the eigenproblem (K, M) of the linearised structure failed");
  const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
  for (int j = 0; j < m; ++j) {
    const double lambda = eigen.eigenvalues()[j];
    if (!(lambda > 1e-12 * largest)) continue;  // rigid-body motion
    LinearMode mode;
    mode.omega = std::sqrt(lambda);
    mode.shape = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd phi = eigen.eigenvectors().col(j);
    phi /= std::sqrt(phi.dot(mm * phi));  // Nᵀ M N is M on the motions: φᵀ M φ = 1 in x too
    // One sign for every run: the largest component positive.
    Eigen::Index largest_at = 0;
    phi.cwiseAbs().maxCoeff(&largest_at);
    if (phi[largest_at] < 0.0) phi = -phi;
    const Eigen::VectorXd x = basis * phi;
    for (int r = 0; r < f; ++r) mode.shape[free[r]] = x[r];
    mode.damping_ratio = mode.shape.dot(lin.damping * mode.shape) / (2.0 * mode.omega);
    modes.push_back(mode);
  }
  return modes;
}

Eigen::VectorXd lawForcesFor(const HbModel& model, const Eigen::VectorXd& needed) {
  const int n = model.structure.dofs();
  int components = 0;
  for (const AttachedLaw& attached : model.laws) components += attached.law->dimension();
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(components);
  Eigen::VectorXd remaining = needed;
  std::vector<bool> taken(n, false);
  std::vector<int> shared;                // components not on one DOF
  std::vector<Eigen::VectorXd> directions;  // their sign · W_aᵀ
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l) {
    const AttachedLaw& attached = model.laws[l];
    const double sign = attached.law->forceSign();
    for (int c = 0; c < attached.law->dimension(); ++c) {
      const int index = model.componentIndex(l, c);
      if (!onOneDof(attached.attachment, c)) {
        shared.push_back(index);
        directions.push_back(sign * attached.attachment.transposeDense(n).col(c));
        continue;
      }
      const int dof = attached.attachment.dof(c);
      if (taken[dof]) continue;
      taken[dof] = true;
      forces[index] = needed[dof] / sign;
      remaining[dof] = 0.0;
    }
  }
  if (!shared.empty()) {
    Eigen::MatrixXd w(n, shared.size());
    for (size_t k = 0; k < shared.size(); ++k) w.col(k) = directions[k];
    const Eigen::VectorXd lambda = w.completeOrthogonalDecomposition().solve(remaining);
    for (size_t k = 0; k < shared.size(); ++k) forces[shared[k]] = lambda[k];
  }
  return forces;
}

}  // namespace eqhb
