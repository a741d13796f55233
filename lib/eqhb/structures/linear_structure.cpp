#include "eqhb/structures/linear_structure.h"

#include <Eigen/SparseCholesky>
#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

namespace {
void checkMatrix(const char* name, const SparseMatrix& m, Eigen::Index n) {
  if (m.rows() != n || m.cols() != n)
    throwInputError(name, std::to_string(m.rows()) + "x" + std::to_string(m.cols()),
                    "must be " + std::to_string(n) + "x" + std::to_string(n));
  for (Eigen::Index e = 0; e < m.nonZeros(); ++e)
    if (!std::isfinite(m.valuePtr()[e])) throwInputError(name, "(matrix)", "contains NaN or Inf");
}
// Whether symmetric m has no direction of negative curvature (relative to
// scale). Small: dense LDLT. Large: the DOFs with a nonzero row, where m must
// be positive definite (sparse LDLT); zero rows are massless DOFs.
bool semidefinite(const SparseMatrix& m, double scale) {
  const Eigen::Index n = m.rows();
  if (n <= 1000) {
    const Eigen::LDLT<Eigen::MatrixXd> ldlt{Eigen::MatrixXd(m)};
    return ldlt.info() == Eigen::Success && !(ldlt.vectorD().array() < -1e-12 * scale).any();
  }
  std::vector<int> index(n, -1);
  int kept = 0;
  for (int j = 0; j < m.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(m, j); it; ++it)
      if (it.value() != 0.0 && index[j] < 0) index[j] = kept++;
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < m.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(m, j); it; ++it)
      if (index[it.row()] >= 0 && index[j] >= 0) entries.emplace_back(index[it.row()], index[j], it.value());
  SparseMatrix restricted(kept, kept);
  restricted.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(restricted);
  return ldlt.info() == Eigen::Success && !(ldlt.vectorD().array() < -1e-12 * scale).any();
}
}  // namespace

LinearStructure LinearStructure::fromMassStiffnessDamping(SparseMatrix mass, SparseMatrix stiffness,
                                                          SparseMatrix damping, std::vector<HarmonicLoad> loads) {
  LinearStructure s;
  s.mass = std::move(mass);
  s.stiffness = std::move(stiffness);
  s.damping = std::move(damping);
  s.loads = std::move(loads);
  s.mass.makeCompressed();
  s.damping.makeCompressed();
  s.stiffness.makeCompressed();
  return s;
}

LinearStructure LinearStructure::fromMassStiffnessDamping(const Eigen::MatrixXd& mass,
                                                          const Eigen::MatrixXd& stiffness,
                                                          const Eigen::MatrixXd& damping,
                                                          std::vector<HarmonicLoad> loads) {
  return fromMassStiffnessDamping(SparseMatrix(mass.sparseView(1.0, 0.0)), SparseMatrix(stiffness.sparseView(1.0, 0.0)),
                                  SparseMatrix(damping.sparseView(1.0, 0.0)), std::move(loads));
}

void LinearStructure::validate() const {
  const Eigen::Index n = mass.rows();
  if (n < 1) throwInputError("mass", "(empty)", "the structure needs at least one DOF");
  checkMatrix("mass", mass, n);
  checkMatrix("damping", damping, n);
  checkMatrix("stiffness", stiffness, n);
  // Positive semidefinite: massless DOFs (zero rows, e.g. contact nodes) are
  // allowed; whether K holds them is checked where the matrices are read.
  const SparseMatrix transposed = mass.transpose();
  const double scale = mass.nonZeros() ? Eigen::Map<const Eigen::VectorXd>(mass.valuePtr(), mass.nonZeros())
                                             .cwiseAbs().maxCoeff()
                                       : 0.0;
  if (!(scale > 0.0) || !semidefinite(0.5 * (mass + transposed), scale) ||
      (mass - transposed).norm() > 1e-12 * mass.norm())
    throwInputError("mass", "(matrix)", "must be symmetric positive semidefinite and not zero");
  for (size_t i = 0; i < loads.size(); ++i) {
    const auto& load = loads[i];
    const std::string field = "forcing[" + std::to_string(i) + "]";
    if (load.dof < 0 || load.dof >= n)
      throwInputError(field + ".dof", std::to_string(load.dof + 1),
                      "no such DOF (the structure has " + std::to_string(n) + ")");
    if (load.harmonic < 0)
      throwInputError(field + ".harmonic", std::to_string(load.harmonic), "must be >= 0");
    if (!std::isfinite(load.cos_amplitude) || !std::isfinite(load.sin_amplitude))
      throwInputError(field, "(amplitude)", "must be finite");
  }
}

SparseMatrix LinearStructure::pattern() const {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(mass.nonZeros() + damping.nonZeros() + stiffness.nonZeros());
  for (const SparseMatrix* m : {&mass, &damping, &stiffness})
    for (int j = 0; j < m->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*m, j); it; ++it) entries.emplace_back(it.row(), j, 1.0);
  SparseMatrix p(dofs(), dofs());
  p.setFromTriplets(entries.begin(), entries.end(), [](double, double) { return 1.0; });
  return p;
}

Eigen::MatrixXd LinearStructure::harmonicOperator(int k, double omega) const {
  if (k == 0) return Eigen::MatrixXd(stiffness);
  const Eigen::Index n = dofs();
  const double kw = k * omega;
  Eigen::MatrixXd a(2 * n, 2 * n);
  const Eigen::MatrixXd diagonal = Eigen::MatrixXd(stiffness) - kw * kw * Eigen::MatrixXd(mass);
  const Eigen::MatrixXd c = Eigen::MatrixXd(damping);
  a.topLeftCorner(n, n) = diagonal;
  a.bottomRightCorner(n, n) = diagonal;
  a.topRightCorner(n, n) = kw * c;
  a.bottomLeftCorner(n, n) = -kw * c;
  return a;
}

SparseMatrix LinearStructure::harmonicOperatorSparse(int k, double omega) const {
  const int n = dofs();
  const double kw = k * omega;
  const SparseMatrix p = pattern();
  // Explicit zeros on the whole pattern first, so that every ω gives the
  // same structure whatever cancels numerically.
  std::vector<Eigen::Triplet<double>> entries;
  const int blocks = k == 0 ? 1 : 2;
  entries.reserve(static_cast<size_t>(blocks * blocks) *
                  (p.nonZeros() + mass.nonZeros() + damping.nonZeros() + stiffness.nonZeros()));
  auto add = [&](const SparseMatrix& m, double scale, int row0, int col0) {
    for (int j = 0; j < m.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(m, j); it; ++it)
        entries.emplace_back(row0 + it.row(), col0 + j, scale * it.value());
  };
  for (int r = 0; r < blocks; ++r)
    for (int c = 0; c < blocks; ++c) add(p, 0.0, r * n, c * n);
  for (int b = 0; b < blocks; ++b) {
    add(stiffness, 1.0, b * n, b * n);
    if (k != 0) add(mass, -kw * kw, b * n, b * n);
  }
  if (k != 0) {
    add(damping, kw, 0, n);
    add(damping, -kw, n, 0);
  }
  SparseMatrix a(blocks * n, blocks * n);
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

}  // namespace eqhb
