#include "eqhb/stability/interface_reduction.h"

#include <algorithm>
#include <cmath>

#include <Spectra/MatOp/DenseSymMatProd.h>
#include <Spectra/MatOp/SymShiftInvert.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include "eqhb/error.h"

namespace eqhb {

namespace {

// (α, β) with C = α M + β K to rounding, if the damping is proportional:
// the least-squares fit over the entries (normal equations on M and K
// scaled to unit size, passes over the matrices but no copies of them).
bool proportionalDamping(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& stiffness, const Eigen::MatrixXd& damping,
                         double& alpha, double& beta) {
  const double mass_size = mass.norm(), stiffness_size = stiffness.norm();
  if (!(mass_size > 0.0) || !(stiffness_size > 0.0)) return false;
  const double cosine = mass.cwiseProduct(stiffness).sum() / (mass_size * stiffness_size);
  const double along_mass = mass.cwiseProduct(damping).sum() / mass_size;
  const double along_stiffness = stiffness.cwiseProduct(damping).sum() / stiffness_size;
  const double determinant = 1.0 - cosine * cosine;
  if (!(determinant > 1e-12)) return false;  // M and K (nearly) parallel: no unique fit
  alpha = (along_mass - cosine * along_stiffness) / determinant / mass_size;
  beta = (along_stiffness - cosine * along_mass) / determinant / stiffness_size;
  const double residual = (damping - alpha * mass - beta * stiffness).norm();
  return std::isfinite(alpha) && std::isfinite(beta) && residual <= 1e-12 * damping.norm();
}

// The modes of K φ = ω² M φ with ω² <= `limit`, lowest first, φᵀ M φ = 1,
// by shift-invert Lanczos at 0 (Spectra), their number counted first from
// the inertia of K − limit M (Sylvester). False when that is not the cheap
// route (more than a quarter of the modes) or it did not converge.
bool lowestModes(const Eigen::MatrixXd& stiffness, const Eigen::MatrixXd& mass, double limit,
                 Eigen::VectorXd& values, Eigen::MatrixXd& vectors) {
  const Eigen::Index n = stiffness.rows();
  const Eigen::LDLT<Eigen::MatrixXd> shifted(stiffness - limit * mass);
  if (shifted.info() != Eigen::Success) return false;
  const Eigen::Index count = (shifted.vectorD().array() < 0.0).count();
  if (count == 0) {
    values.resize(0);
    vectors.resize(n, 0);
    return true;
  }
  if (4 * count > n) return false;
  using Operator = Spectra::SymShiftInvert<double, Eigen::Dense, Eigen::Dense>;
  using MassProduct = Spectra::DenseSymMatProd<double>;
  Operator op(stiffness, mass);
  MassProduct m(mass);
  const Eigen::Index subspace = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * count + 1, 20));
  Spectra::SymGEigsShiftSolver<Operator, MassProduct, Spectra::GEigsMode::ShiftInvert> solver(op, m, count, subspace,
                                                                                            0.0);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  if (solver.info() != Spectra::CompInfo::Successful) return false;
  const Eigen::VectorXd found = solver.eigenvalues();
  const Eigen::MatrixXd found_vectors = solver.eigenvectors();
  std::vector<Eigen::Index> order(count);
  for (Eigen::Index k = 0; k < count; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return found[a] < found[b]; });
  values.resize(count);
  vectors.resize(n, count);
  for (Eigen::Index k = 0; k < count; ++k) {
    values[k] = found[order[k]];
    vectors.col(k) = found_vectors.col(order[k]);
    vectors.col(k) /= std::sqrt(vectors.col(k).dot(mass * vectors.col(k)));
    // A mode found must be one counted (ω² <= limit) and solve the pencil.
    const double size = (stiffness * vectors.col(k)).norm() + std::abs(values[k]) * (mass * vectors.col(k)).norm();
    if (!(values[k] <= limit * (1.0 + 1e-12)) ||
        !((stiffness * vectors.col(k) - values[k] * (mass * vectors.col(k))).norm() <= 1e-8 * size))
      return false;
  }
  return true;
}

}  // namespace

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
  int kept_count = 0;
  if (ni > 0) {
    const Eigen::LDLT<Eigen::MatrixXd> kfactor(kii);
    if (kfactor.info() != Eigen::Success || !(kfactor.vectorD().minCoeff() > 0.0))
      throwInputError("structure", "stiffness", "its interior (away from the laws' DOFs) must be positive definite");
    psi = -kfactor.solve(block(stiffness, interior, boundary));
    const Eigen::MatrixXd cii = block(damping, interior, interior);
    // With proportional damping (β > 0) a mode's σ = (α + β ω²)/2 grows
    // with ω, so the kept modes are the lowest ones, ω² up to the larger of
    // fast_rate² and (2 decay / T − α)/β: those alone are computed (beam-
    // damper: 1 of 115, 0.2 ms against 3 ms for every mode).
    double alpha = 0.0, beta = 0.0;
    Eigen::VectorXd values;
    bool found = false;
    if (proportionalDamping(mii, kii, cii, alpha, beta) && beta > 0.0) {
      const double limit = std::max(fast_rate * fast_rate, (2.0 * decay / period - alpha) / beta);
      found = lowestModes(kii, mii, limit, values, phi);
    }
    if (!found) {
      const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(kii, mii);
      if (modes.info() != Eigen::Success)
        throwInputError("structure", "mass", "the interior's modes did not converge");
      const Eigen::MatrixXd& vectors = modes.eigenvectors();
      const Eigen::MatrixXd damped = cii * vectors;  // one product for every mode
      std::vector<int> kept;
      for (int k = 0; k < ni; ++k) {
        const double rate = std::sqrt(std::max(modes.eigenvalues()[k], 0.0));
        const double sigma = 0.5 * vectors.col(k).dot(damped.col(k));
        if (rate > fast_rate && sigma * period > decay) continue;
        kept.push_back(k);
      }
      phi.resize(ni, kept.size());
      for (size_t k = 0; k < kept.size(); ++k) phi.col(k) = vectors.col(kept[k]);
    }
    kept_count = static_cast<int>(phi.cols());
    out.modes_kept = kept_count;
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
