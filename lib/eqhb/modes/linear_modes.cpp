#include "eqhb/modes/linear_modes.h"

#include <cmath>
#include <stdexcept>

#include "eqhb/laws/grounded_laws.h"

namespace eqhb {

namespace {
// The partials (a, b, c, e) of component `a` of `law` at rest.
struct RestPartials {
  double displacement = 0.0, velocity = 0.0, force = 0.0, force_rate = 0.0;
};

RestPartials partialsAtRest(const Law& law, int component) {
  const int d = law.dimension();
  LawSamples samples;
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
}  // namespace

LinearisedStructure linearisedStructure(const HbModel& model) {
  const LinearStructure& s = model.structure;
  const int n = s.dofs();
  LinearisedStructure out;
  out.stiffness = Eigen::MatrixXd(s.stiffness);
  out.damping = Eigen::MatrixXd(s.damping);
  out.held.assign(n, false);
  requireGroundedLaws(model.laws, "nonlinear modes");
  for (const AttachedLaw& attached : model.laws) {
    const Law& law = *attached.law;
    for (int a = 0; a < law.dimension(); ++a) {
      const RestPartials p = partialsAtRest(law, a);
      const int i = attached.attachment.dof(a);
      const double sign = law.forceSign();
      if (p.force != 0.0) {
        out.stiffness(i, i) += sign * p.displacement / p.force;
        out.damping(i, i) += sign * p.velocity / p.force;
      } else if (p.force_rate != 0.0) {
        out.stiffness(i, i) += sign * p.velocity / p.force_rate;
      } else if (p.displacement != 0.0 || p.velocity != 0.0) {
        out.held[i] = true;
      }
    }
  }
  return out;
}

std::vector<LinearMode> linearModes(const HbModel& model) {
  const LinearisedStructure lin = linearisedStructure(model);
  const Eigen::MatrixXd mass(model.structure.mass);
  const int n = model.structure.dofs();
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (!lin.held[i]) free.push_back(i);
  const int m = static_cast<int>(free.size());
  std::vector<LinearMode> modes;
  if (m == 0) return modes;
  Eigen::MatrixXd k(m, m), mm(m, m);
  for (int r = 0; r < m; ++r)
    for (int c = 0; c < m; ++c) {
      k(r, c) = lin.stiffness(free[r], free[c]);
      mm(r, c) = mass(free[r], free[c]);
    }
  // Symmetrised: the laws' springs are on the diagonal, K and M symmetric.
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
    phi /= std::sqrt(phi.dot(mm * phi));
    // One sign for every run: the largest component positive.
    Eigen::Index largest_at = 0;
    phi.cwiseAbs().maxCoeff(&largest_at);
    if (phi[largest_at] < 0.0) phi = -phi;
    for (int r = 0; r < m; ++r) mode.shape[free[r]] = phi[r];
    mode.damping_ratio = mode.shape.dot(lin.damping * mode.shape) / (2.0 * mode.omega);
    modes.push_back(mode);
  }
  return modes;
}

}  // namespace eqhb
