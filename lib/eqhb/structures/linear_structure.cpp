#include "eqhb/structures/linear_structure.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

namespace {
void checkMatrix(const char* name, const Eigen::MatrixXd& m, Eigen::Index n) {
  if (m.rows() != n || m.cols() != n)
    throwInputError(name, std::to_string(m.rows()) + "x" + std::to_string(m.cols()),
                    "must be " + std::to_string(n) + "x" + std::to_string(n));
  if (!m.allFinite()) throwInputError(name, "(matrix)", "contains NaN or Inf");
}
}  // namespace

void LinearStructure::validate() const {
  const Eigen::Index n = mass.rows();
  if (n < 1) throwInputError("mass", "(empty)", "the structure needs at least one DOF");
  checkMatrix("mass", mass, n);
  checkMatrix("damping", damping, n);
  checkMatrix("stiffness", stiffness, n);
  // Positive semidefinite: massless DOFs (zero rows, e.g. contact nodes) are
  // allowed; whether K holds them is checked where the matrices are read.
  Eigen::LDLT<Eigen::MatrixXd> ldlt(0.5 * (mass + mass.transpose()));
  const double scale = mass.cwiseAbs().maxCoeff();
  if (ldlt.info() != Eigen::Success || !(scale > 0.0) ||
      (ldlt.vectorD().array() < -1e-12 * scale).any() ||
      (mass - mass.transpose()).norm() > 1e-12 * mass.norm())
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

Eigen::MatrixXd LinearStructure::harmonicOperator(int k, double omega) const {
  if (k == 0) return stiffness;
  const Eigen::Index n = dofs();
  const double kw = k * omega;
  Eigen::MatrixXd a(2 * n, 2 * n);
  const Eigen::MatrixXd diagonal = stiffness - kw * kw * mass;
  a.topLeftCorner(n, n) = diagonal;
  a.bottomRightCorner(n, n) = diagonal;
  a.topRightCorner(n, n) = kw * damping;
  a.bottomLeftCorner(n, n) = -kw * damping;
  return a;
}

}  // namespace eqhb
