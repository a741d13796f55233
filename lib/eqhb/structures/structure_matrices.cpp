#include "eqhb/structures/structure_matrices.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/structures/matrix_market.h"

namespace eqhb {

StructureMatrices fromElementTriplets(int n, const std::vector<Eigen::Triplet<double>>& mass,
                                      const std::vector<Eigen::Triplet<double>>& stiffness) {
  StructureMatrices s;
  s.mass.resize(n, n);
  s.stiffness.resize(n, n);
  s.damping.resize(n, n);
  s.mass.setFromTriplets(mass.begin(), mass.end());
  s.stiffness.setFromTriplets(stiffness.begin(), stiffness.end());
  return s;
}

namespace {

double largestEntry(const Eigen::SparseMatrix<double>& m) {
  double largest = 0.0;
  for (int c = 0; c < m.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, c); it; ++it) largest = std::max(largest, std::abs(it.value()));
  return largest;
}

// The principal submatrix of `m` on the DOFs `keep` (sorted).
Eigen::SparseMatrix<double> principal(const Eigen::SparseMatrix<double>& m, const std::vector<int>& keep) {
  std::vector<int> position(m.rows(), -1);
  for (size_t i = 0; i < keep.size(); ++i) position[keep[i]] = static_cast<int>(i);
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < m.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, c); it; ++it)
      if (position[it.row()] >= 0 && position[it.col()] >= 0) t.emplace_back(position[it.row()], position[it.col()], it.value());
  Eigen::SparseMatrix<double> out(keep.size(), keep.size());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

void checkOne(const Eigen::SparseMatrix<double>& m, const std::string& name, Eigen::Index n, double tolerance) {
  if (m.rows() != m.cols())
    throw InputError(name + ": must be square, is " + std::to_string(m.rows()) + " x " + std::to_string(m.cols()));
  if (m.rows() != n)
    throw InputError(name + ": is " + std::to_string(m.rows()) + " x " + std::to_string(m.cols()) +
                     ", the mass matrix is " + std::to_string(n) + " x " + std::to_string(n) + " (sizes must agree)");
  for (int c = 0; c < m.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, c); it; ++it)
      if (!std::isfinite(it.value()))
        throw InputError(name + ": entry (" + std::to_string(it.row() + 1) + ", " + std::to_string(it.col() + 1) +
                         ") is NaN or Inf");
  const double asymmetry = relativeAsymmetry(m);
  if (asymmetry > tolerance)
    throw InputError(name + ": not symmetric: max |A_ij - A_ji| / max |A_ij| = " + formatNumber(asymmetry) +
                     " exceeds the relative tolerance " + formatNumber(tolerance) +
                     " (structure.symmetry_tolerance)");
}

}  // namespace

Eigen::SparseMatrix<double> rayleighDamping(const StructureMatrices& s, double alpha, double beta) {
  Eigen::SparseMatrix<double> c = alpha * s.mass + beta * s.stiffness;
  c.prune(0.0);
  return c;
}

void checkModalDampingSize(int dofs, double ratio, const std::string& field, int max_dofs) {
  if (dofs > max_dofs)
    throwInputError(field, formatNumber(ratio),
                    "modal damping forms a dense C; with " + std::to_string(dofs) + " DOFs (more than " +
                        std::to_string(max_dofs) + ") use rayleigh = [alpha, beta]");
}

Eigen::SparseMatrix<double> modalDamping(const StructureMatrices& s, double ratio, const std::string& field,
                                         int max_dofs) {
  checkModalDampingSize(s.dofs(), ratio, field, max_dofs);
  const Eigen::MatrixXd m(s.mass), k(s.stiffness);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k, m);
  if (eigen.info() != Eigen::Success)
    throwInputError(field, formatNumber(ratio),
                    "modal damping needs a positive definite mass matrix (massless DOFs: use rayleigh)");
  const Eigen::MatrixXd& phi = eigen.eigenvectors();  // mass-normalised
  const Eigen::VectorXd omega = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::MatrixXd mphi = m * phi;
  const Eigen::MatrixXd c = mphi * (2.0 * ratio * omega).asDiagonal() * mphi.transpose();
  Eigen::MatrixXd symmetric = 0.5 * (c + c.transpose());
  return symmetric.sparseView(1e-14 * symmetric.cwiseAbs().maxCoeff(), 1.0);
}

namespace {
// xᵀ A x >= 0 for every x (K stores energy, C dissipates it; the chain's
// k >= 0, d >= 0 in matrix form): the symmetric part shifted by
// 1e-12 max|A| has a sparse Cholesky factor.
void checkSemidefinite(const Eigen::SparseMatrix<double>& a, const std::string& name) {
  const double scale = largestEntry(a);
  if (scale == 0.0) return;
  const Eigen::SparseMatrix<double> transposed = a.transpose();
  Eigen::SparseMatrix<double> identity(a.rows(), a.cols());
  identity.setIdentity();
  const Eigen::SparseMatrix<double> shifted = 0.5 * (a + transposed) + 1e-12 * scale * identity;
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> factor(shifted);
  if (factor.info() != Eigen::Success)
    throw InputError(name + ": must be positive semidefinite (it has a negative direction: negative stiffness "
                            "or damping)");
}
}  // namespace

void checkStructureMatrices(const StructureMatrices& s, double symmetry_tolerance, const MatrixNames& names) {
  const Eigen::Index n = s.mass.rows();
  if (n < 1) throw InputError(names.mass + ": the structure needs at least one DOF");
  checkOne(s.mass, names.mass, n, symmetry_tolerance);
  checkOne(s.stiffness, names.stiffness, n, symmetry_tolerance);
  checkOne(s.damping, names.damping, n, symmetry_tolerance);

  // Massless DOFs: rows of M without a nonzero entry.
  std::vector<bool> has_mass(n, false);
  for (int c = 0; c < s.mass.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(s.mass, c); it; ++it)
      if (it.value() != 0.0) has_mass[it.row()] = true;
  std::vector<int> massive, massless;
  for (int i = 0; i < n; ++i) (has_mass[i] ? massive : massless).push_back(i);
  if (massive.empty()) throw InputError(names.mass + ": every row is zero (no DOF carries mass)");

  // M on its massive DOFs must be positive definite (a negative or zero mode
  // of M would be non-physical).
  const Eigen::SparseMatrix<double> m_massive = principal(s.mass, massive);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> mass_factor(m_massive);
  const double m_scale = largestEntry(m_massive);
  if (mass_factor.info() != Eigen::Success ||
      (mass_factor.vectorD().array() <= 1e-13 * m_scale).any())
    throw InputError(names.mass + ": must be positive semidefinite with a positive definite block on the DOFs "
                                  "that carry mass (found a zero or negative mass direction)");
  if (!massless.empty()) {
    const Eigen::SparseMatrix<double> k_massless = principal(s.stiffness, massless);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> stiffness_factor(k_massless);
    const double k_scale = largestEntry(s.stiffness);
    if (stiffness_factor.info() != Eigen::Success || k_scale == 0.0 ||
        (stiffness_factor.vectorD().array().abs() <= 1e-12 * k_scale).any())
      throw InputError(names.stiffness + ": the " + std::to_string(massless.size()) +
                       " massless DOF(s) (zero rows of the mass matrix, first DOF " + std::to_string(massless[0] + 1) +
                       ") are not held by the stiffness: K restricted to them is singular, so the system is not regular");
  }
  checkSemidefinite(s.stiffness, names.stiffness);
  checkSemidefinite(s.damping, names.damping);
}

LinearStructure toLinearStructure(const StructureMatrices& s) {
  return LinearStructure::fromMassStiffnessDamping(s.mass, s.stiffness, s.damping);
}

}  // namespace eqhb
