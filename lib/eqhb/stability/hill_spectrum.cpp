#include "eqhb/stability/hill_spectrum.h"

#include <Spectra/GenEigsSolver.h>

#include <algorithm>
#include <vector>

namespace eqhb {

namespace {

using Triplet = Eigen::Triplet<double>;

// Shifts tried in turn where A − σB is singular: σ in units of ω.
constexpr double kShifts[] = {0.0, -0.0137, 0.0291};

// u ↦ E (A − σB)⁻¹ B̃ u through a sparse LU, for Spectra. With `solved` =
// n0 (σ = 0, A = diag(J, I)) the LU is J's: the top n0 rows of the solution
// are J⁻¹ times those of B̃ u, the rest B̃ u itself; with `solved` = the
// pencil's size it is the LU of A − σB.
class ShiftInvertOperator {
 public:
  using Scalar = double;
  ShiftInvertOperator(const HillPencil& pencil, const Eigen::SparseLU<SparseMatrix>& lu, int solved)
      : pencil_(pencil), lu_(lu), solved_(solved), rhs_(pencil.size), solution_(pencil.size) {}
  Eigen::Index rows() const { return static_cast<Eigen::Index>(pencil_.columns.size()); }
  Eigen::Index cols() const { return rows(); }
  void perform_op(const double* in, double* out) const {
    rhs_.noalias() = pencil_.b_columns * Eigen::Map<const Eigen::VectorXd>(in, rows());
    solution_.head(solved_) = lu_.solve(rhs_.head(solved_));
    for (Eigen::Index c = 0; c < rows(); ++c) {
      const int r = pencil_.columns[c];
      out[c] = r < solved_ ? solution_[r] : rhs_[r];
    }
  }

 private:
  const HillPencil& pencil_;
  const Eigen::SparseLU<SparseMatrix>& lu_;
  const int solved_;
  mutable Eigen::VectorXd rhs_, solution_;
};

// Spectra's solver, whose eigenvectors are asked for their leading rows only
// (the displacement part that the centroid reads) and formed by two real
// products V·Re + i V·Im instead of one mixed real-complex product.
class HillArnoldi : public Spectra::GenEigsSolver<ShiftInvertOperator> {
 public:
  using Spectra::GenEigsSolver<ShiftInvertOperator>::GenEigsSolver;
  // Rows [0, rows) of the Ritz vectors; valid after a successful compute()
  // (all nev converged, in eigenvalues()' order).
  Eigen::MatrixXcd leadingRows(Eigen::Index rows) const {
    const auto v = m_fac.matrix_V().topRows(rows);
    const Eigen::MatrixXd re = v * m_ritz_vec.real(), im = v * m_ritz_vec.imag();
    Eigen::MatrixXcd out(rows, m_nev);
    out.real() = re;
    out.imag() = im;
    return out;
  }
};

// Scales each row of `a` to a largest entry of 1 and returns the factors D
// (1 for a zero row): (D A)⁻¹ D B = A⁻¹ B, while the test of singularity by
// rcond no longer reads a structure's units as singularity (a beam in SI
// units: stiffness rows of 1e8 against law rows of 1, every shift judged
// singular).
Eigen::VectorXd equilibrate(Eigen::MatrixXd& a) {
  Eigen::VectorXd d = a.cwiseAbs().rowwise().maxCoeff();
  for (Eigen::Index i = 0; i < d.size(); ++i) d[i] = d[i] > 0.0 ? 1.0 / d[i] : 1.0;
  a = d.asDiagonal() * a;
  return d;
}

// E (A − σB)⁻¹ B̃ at σ = 0, dense. A = diag(J, I): J [p; q] = (B̃ x) on the top
// n0 rows and w = (B̃ x) on the rest, so only J is factorised (n0 of the
// pencil's unknowns). Singular as diag(J, I) would be judged: rcond(A) from
// J's with ‖A‖₁ = max(‖J‖₁, 1) and ‖A⁻¹‖₁ = max(‖J⁻¹‖₁, 1). False if singular.
bool reducedAtZeroShift(const HillPencil& pencil, const Eigen::MatrixXd& b_columns, Eigen::MatrixXd& reduced) {
  const int n0 = pencil.jacobian_size, m = static_cast<int>(pencil.columns.size());
  Eigen::MatrixXd j = Eigen::MatrixXd(pencil.a.topLeftCorner(n0, n0));
  const Eigen::VectorXd rows = equilibrate(j);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(j);
  const double norm = j.cwiseAbs().colwise().sum().maxCoeff();
  const double inverse_norm = 1.0 / (lu.rcond() * norm);
  if (!(1.0 / (std::max(norm, 1.0) * std::max(inverse_norm, 1.0)) > 1e-14)) return false;
  const Eigen::MatrixXd solved = lu.solve(rows.asDiagonal() * b_columns.topRows(n0));
  for (int c = 0; c < m; ++c) {
    const int r = pencil.columns[c];
    reduced.row(c) = r < n0 ? solved.row(r) : b_columns.row(r);
  }
  return true;
}

// The same at σ ≠ 0 (J singular), where the whole A and B are needed dense.
bool reducedAtShift(const HillPencil& pencil, const Eigen::MatrixXd& b_columns, double sigma,
                    Eigen::MatrixXd& reduced) {
  const int m = static_cast<int>(pencil.columns.size());
  Eigen::MatrixXd a_shifted = Eigen::MatrixXd(pencil.a);
  for (size_t c = 0; c < pencil.columns.size(); ++c) a_shifted.col(pencil.columns[c]) -= sigma * b_columns.col(c);
  const Eigen::VectorXd rows = equilibrate(a_shifted);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a_shifted);
  if (!(lu.rcond() > 1e-14)) return false;
  const Eigen::MatrixXd solved = lu.solve(rows.asDiagonal() * b_columns);
  for (int c = 0; c < m; ++c) reduced.row(c) = solved.row(pencil.columns[c]);
  return true;
}

// B as a square matrix over all of u (B̃'s columns put back in their places).
SparseMatrix fullB(const HillPencil& pencil) {
  SparseMatrix b(pencil.size, pencil.size);
  std::vector<Triplet> entries;
  for (int c = 0; c < pencil.b_columns.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(pencil.b_columns, c); it; ++it)
      entries.emplace_back(it.row(), pencil.columns[c], it.value());
  b.setFromTriplets(entries.begin(), entries.end());
  return b;
}

}  // namespace

double largestModulus(const Eigen::VectorXcd& values) {
  double largest = 0.0;
  for (Eigen::Index j = 0; j < values.size(); ++j) largest = std::max(largest, std::abs(values[j]));
  return largest;
}

bool denseHillSpectrum(const HillPencil& pencil, double omega, double exponent_limit, DenseEigenproblem& solver,
                       HillSpectrum* out, std::string* failure) {
  const Eigen::MatrixXd b_columns = Eigen::MatrixXd(pencil.b_columns);
  const int m = static_cast<int>(pencil.columns.size());
  Eigen::MatrixXd reduced(m, m);
  for (double shift : kShifts) {
    const double sigma = shift * omega;
    const bool regular = sigma == 0.0 ? reducedAtZeroShift(pencil, b_columns, reduced)
                                      : reducedAtShift(pencil, b_columns, sigma, reduced);
    if (!regular || !solver.compute(reduced)) continue;
    out->values = solver.eigenvalues();
    // Vectors of the finite eigenvalues only, the candidates.
    std::vector<int> finite;
    const FiniteExponent isFinite{largestModulus(out->values), sigma, exponent_limit};
    for (Eigen::Index j = 0; j < out->values.size(); ++j)
      if (isFinite(out->values[j])) finite.push_back(static_cast<int>(j));
    Eigen::MatrixXcd vectors;
    solver.eigenvectors(finite, &vectors);
    out->vectors.setZero(reduced.rows(), reduced.cols());
    for (size_t c = 0; c < finite.size(); ++c) out->vectors.col(finite[c]) = vectors.col(c);
    out->shift = sigma;
    return true;
  }
  *failure = "the Hill pencil is singular at every shift tried";
  return false;
}

bool sparseHillSpectrum(const HillPencil& pencil, double omega, int wanted, const SparseMatrix& jacobian,
                        JacobianLu& jacobian_lu, HillSpectrum* out, std::string* failure) {
  const SparseMatrix b = fullB(pencil);
  const int m = static_cast<int>(pencil.columns.size());
  const int nev = std::clamp(wanted, 1, m - 2);
  const int ncv = std::min(m, std::max(2 * nev + 1, nev + 20));
  for (double shift : kShifts) {
    const double sigma = shift * omega;
    Eigen::SparseLU<SparseMatrix> shifted_lu;
    const Eigen::SparseLU<SparseMatrix>* lu = &jacobian_lu.lu;
    int solved = pencil.jacobian_size;
    if (sigma == 0.0) {
      if (!jacobian_lu.analysed) jacobian_lu.lu.analyzePattern(jacobian);
      jacobian_lu.analysed = true;
      jacobian_lu.lu.factorize(jacobian);
      if (jacobian_lu.lu.info() != Eigen::Success) continue;
    } else {
      SparseMatrix shifted = pencil.a - sigma * b;
      shifted.makeCompressed();
      shifted_lu.compute(shifted);
      if (shifted_lu.info() != Eigen::Success) continue;
      lu = &shifted_lu;
      solved = pencil.size;
    }
    ShiftInvertOperator op(pencil, *lu, solved);
    HillArnoldi solver(op, nev, ncv);
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10);
    if (solver.info() != Spectra::CompInfo::Successful) {
      *failure = "the Arnoldi solver did not converge";
      continue;
    }
    out->values = solver.eigenvalues();
    out->vectors = solver.leadingRows(pencil.displacement_unknowns);
    out->shift = sigma;
    return true;
  }
  if (failure->empty()) *failure = "the Hill pencil is singular at every shift tried";
  return false;
}

}  // namespace eqhb
