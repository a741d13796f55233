#include "eqhb/stability/interface_reduction.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SparseCholesky>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/MatOp/SymShiftInvert.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include "eqhb/error.h"

namespace eqhb {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// (α, β) with C = α M + β K to rounding, if the damping is proportional:
// the least-squares fit over the entries (normal equations on M and K
// scaled to unit size, passes over the matrices but no copies of them).
bool proportionalDamping(const SparseMatrix& mass, const SparseMatrix& stiffness, const SparseMatrix& damping,
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
// by shift-invert Lanczos at 0 (Spectra, on the sparse matrices), their
// number counted first from the inertia of K − limit M (Sylvester, by a
// sparse LDLᵀ) and checked by one mode more, which must lie above the
// limit. False when that is not the cheap route (more than a quarter of the
// modes), the count is not confirmed or it did not converge.
bool lowestModes(const SparseMatrix& stiffness, const SparseMatrix& mass, double limit, Eigen::VectorXd& values,
                 Eigen::MatrixXd& vectors) {
  const Eigen::Index n = stiffness.rows();
  const SparseMatrix difference = stiffness - limit * mass;
  const Eigen::SimplicialLDLT<SparseMatrix> shifted(difference);
  if (shifted.info() != Eigen::Success || !shifted.vectorD().allFinite()) return false;
  const Eigen::Index count = (shifted.vectorD().array() < 0.0).count();
  if (4 * count > n) return false;
  const Eigen::Index wanted = std::min<Eigen::Index>(count + 1, n - 1);  // one more, to confirm the count
  if (wanted < 1) return false;
  using Operator = Spectra::SymShiftInvert<double, Eigen::Sparse, Eigen::Sparse>;
  using MassProduct = Spectra::SparseSymMatProd<double>;
  Operator op(stiffness, mass);
  MassProduct m(mass);
  const Eigen::Index subspace = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * wanted + 1, 20));
  Spectra::SymGEigsShiftSolver<Operator, MassProduct, Spectra::GEigsMode::ShiftInvert> solver(op, m, wanted, subspace,
                                                                                            0.0);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  if (solver.info() != Spectra::CompInfo::Successful) return false;
  const Eigen::VectorXd found = solver.eigenvalues();
  const Eigen::MatrixXd found_vectors = solver.eigenvectors();
  std::vector<Eigen::Index> order(wanted);
  for (Eigen::Index k = 0; k < wanted; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return found[a] < found[b]; });
  if (count < wanted && !(found[order[count]] > limit * (1.0 - 1e-12))) return false;  // the count is short
  values.resize(count);
  vectors.resize(n, count);
  // The pencil's size for the backward error: ‖K v − ω² M v‖ against
  // (‖K‖ + ω² ‖M‖) ‖v‖. A stiff beam's low mode has ‖K v‖ far below
  // ‖K‖ ‖v‖ (its strain energy is small), so ‖K v‖ is no scale there.
  auto rowSumNorm = [](const SparseMatrix& a) {
    return Eigen::VectorXd(a.cwiseAbs() * Eigen::VectorXd::Ones(a.cols())).maxCoeff();
  };
  const double stiffness_norm = rowSumNorm(stiffness), mass_norm = rowSumNorm(mass);
  for (Eigen::Index k = 0; k < count; ++k) {
    values[k] = found[order[k]];
    vectors.col(k) = found_vectors.col(order[k]);
    vectors.col(k) /= std::sqrt(vectors.col(k).dot(mass * vectors.col(k)));
    // A mode found must be one counted (ω² <= limit) and solve the pencil.
    const Eigen::VectorXd kv = stiffness * vectors.col(k), mv = mass * vectors.col(k);
    const double size = (stiffness_norm + std::abs(values[k]) * mass_norm) * vectors.col(k).lpNorm<Eigen::Infinity>();
    if (!(values[k] <= limit * (1.0 + 1e-12)) ||
        !((kv - values[k] * mv).lpNorm<Eigen::Infinity>() <= 1e-10 * size))
      return false;
  }
  return true;
}

// The blocks of a symmetric sparse matrix on the interior (sparse) and
// interior x boundary (dense): `place[j]` is DOF j's index in its part,
// `inside[j]` whether it is interior.
struct Split {
  SparseMatrix interior;
  Eigen::MatrixXd coupling;  // ni x nb
};
Split split(const SparseMatrix& a, const std::vector<int>& place, const std::vector<char>& inside, int ni, int nb) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(a.nonZeros()));
  Split out;
  out.coupling = Eigen::MatrixXd::Zero(ni, nb);
  for (int j = 0; j < a.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
      const int i = static_cast<int>(it.row());
      if (!inside[i]) continue;
      if (inside[j]) entries.emplace_back(place[i], place[j], it.value());
      else out.coupling(place[i], place[j]) += it.value();
    }
  out.interior.resize(ni, ni);
  out.interior.setFromTriplets(entries.begin(), entries.end());
  return out;
}

}  // namespace

InterfaceReduction reduceToInterface(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                                     const Eigen::MatrixXd& stiffness, std::vector<int> boundary, double fast_rate,
                                     double period, double decay) {
  return reduceToInterface(SparseMatrix(mass.sparseView()), SparseMatrix(damping.sparseView()),
                           SparseMatrix(stiffness.sparseView()), std::move(boundary), fast_rate, period, decay);
}

InterfaceReduction reduceToInterface(const SparseMatrix& mass, const SparseMatrix& damping,
                                     const SparseMatrix& stiffness, std::vector<int> boundary, double fast_rate,
                                     double period, double decay) {
  const int n = static_cast<int>(mass.rows());
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  const int nb = static_cast<int>(boundary.size()), ni = n - nb;
  std::vector<int> interior, place(n);
  std::vector<char> inside(n, 1);
  for (int j = 0; j < nb; ++j) {
    inside[boundary[j]] = 0;
    place[boundary[j]] = j;
  }
  for (int i = 0; i < n; ++i)
    if (inside[i]) {
      place[i] = static_cast<int>(interior.size());
      interior.push_back(i);
    }
  InterfaceReduction out;
  out.boundary = boundary;
  const Split k = split(stiffness, place, inside, ni, nb), mi = split(mass, place, inside, ni, nb);
  const SparseMatrix& kii = k.interior;
  const SparseMatrix& mii = mi.interior;
  Eigen::MatrixXd psi = Eigen::MatrixXd::Zero(ni, nb), phi(ni, 0);
  if (ni > 0) {
    const Eigen::SimplicialLDLT<SparseMatrix> kfactor(kii);
    if (kfactor.info() != Eigen::Success || !(kfactor.vectorD().minCoeff() > 0.0))
      throwInputError("structure", "stiffness", "its interior (away from the laws' DOFs) must be positive definite");
    psi = -kfactor.solve(k.coupling);
    const SparseMatrix cii = split(damping, place, inside, ni, nb).interior;
    // With proportional damping (β > 0) a mode's σ = (α + β ω²)/2 grows
    // with ω, so the kept modes are the lowest ones, ω² up to the larger of
    // fast_rate² and (2 decay / T − α)/β: those alone are computed (beam-
    // damper: 1 of 115; beam-joint-large: 1999 DOFs reduced on sparse
    // matrices, where the dense route took 11 s).
    double alpha = 0.0, beta = 0.0;
    Eigen::VectorXd values;
    bool found = false;
    if (proportionalDamping(mii, kii, cii, alpha, beta) && beta > 0.0) {
      const double limit = std::max(fast_rate * fast_rate, (2.0 * decay / period - alpha) / beta);
      found = lowestModes(kii, mii, limit, values, phi);
    }
    if (!found) {
      const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes{Eigen::MatrixXd(kii),
                                                                            Eigen::MatrixXd(mii)};
      if (modes.info() != Eigen::Success)
        throwInputError("structure", "mass", "the interior's modes did not converge");
      const Eigen::MatrixXd& vectors = modes.eigenvectors();
      const Eigen::MatrixXd damped = cii * vectors;  // one product for every mode
      std::vector<int> kept;
      for (int j = 0; j < ni; ++j) {
        const double rate = std::sqrt(std::max(modes.eigenvalues()[j], 0.0));
        const double sigma = 0.5 * vectors.col(j).dot(damped.col(j));
        if (rate > fast_rate && sigma * period > decay) continue;
        kept.push_back(j);
      }
      phi.resize(ni, kept.size());
      for (size_t j = 0; j < kept.size(); ++j) phi.col(j) = vectors.col(kept[j]);
    }
    out.modes_kept = static_cast<int>(phi.cols());
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
  const Eigen::MatrixXd phim = (mii * phi).transpose();  // modes x ni (M_ii symmetric)
  const Eigen::MatrixXd phimpsi = phim * psi;            // modes x nb
  for (int j = 0; j < out.modes_kept; ++j) {
    for (int i = 0; i < ni; ++i) {
      out.basis(interior[i], nb + j) = phi(i, j);
      out.projection(nb + j, interior[i]) = phim(j, i);
    }
    for (int b = 0; b < nb; ++b) out.projection(nb + j, boundary[b]) = -phimpsi(j, b);
  }
  out.mass = out.basis.transpose() * (mass * out.basis);
  out.damping = out.basis.transpose() * (damping * out.basis);
  out.stiffness = out.basis.transpose() * (stiffness * out.basis);
  return out;
}

}  // namespace eqhb
