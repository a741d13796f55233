#include "eqhb/stability/interface_reduction.h"

#include <algorithm>
#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

InterfaceReduction reduceToInterface(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                                     const Eigen::MatrixXd& stiffness, std::vector<int> boundary, double fast_rate,
                                     double period, double decay) {
  const int n = static_cast<int>(mass.rows());
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  const int nb = static_cast<int>(boundary.size()), ni = n - nb;
  std::vector<int> interior;
  for (int i = 0, j = 0; i < n; ++i) {
    if (j < nb && boundary[j] == i) {
      ++j;
      continue;
    }
    interior.push_back(i);
  }
  auto block = [](const Eigen::MatrixXd& a, const std::vector<int>& rows, const std::vector<int>& cols) {
    Eigen::MatrixXd out(rows.size(), cols.size());
    for (size_t r = 0; r < rows.size(); ++r)
      for (size_t c = 0; c < cols.size(); ++c) out(r, c) = a(rows[r], cols[c]);
    return out;
  };
  InterfaceReduction out;
  out.boundary = boundary;
  const Eigen::MatrixXd kii = block(stiffness, interior, interior), mii = block(mass, interior, interior);
  Eigen::MatrixXd psi = Eigen::MatrixXd::Zero(ni, nb), phi(ni, 0);
  if (ni > 0) {
    const Eigen::LDLT<Eigen::MatrixXd> kfactor(kii);
    if (kfactor.info() != Eigen::Success || !(kfactor.vectorD().minCoeff() > 0.0))
      throwInputError("structure", "stiffness", "its interior (away from the laws' DOFs) must be positive definite");
    psi = -kfactor.solve(block(stiffness, interior, boundary));
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(kii, mii);
    if (modes.info() != Eigen::Success)
      throwInputError("structure", "mass", "the interior's modes did not converge");
    const Eigen::MatrixXd& vectors = modes.eigenvectors();
    const Eigen::MatrixXd damped = block(damping, interior, interior) * vectors;  // one product for every mode
    std::vector<int> kept;
    for (int k = 0; k < ni; ++k) {
      const double rate = std::sqrt(std::max(modes.eigenvalues()[k], 0.0));
      const double sigma = 0.5 * vectors.col(k).dot(damped.col(k));
      if (rate > fast_rate && sigma * period > decay) continue;
      kept.push_back(k);
    }
    phi.resize(ni, kept.size());
    for (size_t k = 0; k < kept.size(); ++k) phi.col(k) = modes.eigenvectors().col(kept[k]);
    out.modes_kept = static_cast<int>(kept.size());
    out.modes_dropped = ni - out.modes_kept;
  }
  const int m = nb + out.modes_kept;
  out.basis = Eigen::MatrixXd::Zero(n, m);
  out.projection = Eigen::MatrixXd::Zero(m, n);
  for (int j = 0; j < nb; ++j) {
    out.basis(boundary[j], j) = 1.0;
    out.projection(j, boundary[j]) = 1.0;
    for (int i = 0; i < ni; ++i) out.basis(interior[i], j) = psi(i, j);
  }
  // η = Φᵀ M_ii (x_i − Ψ x_b)
  const Eigen::MatrixXd phim = phi.transpose() * mii;  // modes x ni
  const Eigen::MatrixXd phimpsi = phim * psi;          // modes x nb
  for (int k = 0; k < out.modes_kept; ++k) {
    for (int i = 0; i < ni; ++i) {
      out.basis(interior[i], nb + k) = phi(i, k);
      out.projection(nb + k, interior[i]) = phim(k, i);
    }
    for (int j = 0; j < nb; ++j) out.projection(nb + k, boundary[j]) = -phimpsi(k, j);
  }
  out.mass = out.basis.transpose() * mass * out.basis;
  out.damping = out.basis.transpose() * damping * out.basis;
  out.stiffness = out.basis.transpose() * stiffness * out.basis;
  return out;
}

}  // namespace eqhb
