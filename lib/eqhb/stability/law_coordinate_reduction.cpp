// reduceToLawCoordinates (interface_reduction.h): the change to the laws'
// coordinates y = E x, the DOF reduction on y, and the way back to x.
#include <algorithm>

#include "eqhb/stability/interface_reduction.h"

namespace eqhb {

std::optional<LawCoordinateReduction> reduceToLawCoordinates(const Eigen::MatrixXd& mass,
                                                             const Eigen::MatrixXd& damping,
                                                             const Eigen::MatrixXd& stiffness,
                                                             const Eigen::MatrixXd& directions, double fast_rate,
                                                             double period, double decay) {
  const Eigen::Index n = directions.rows(), b = directions.cols();
  if (b == 0 || b > n) return std::nullopt;
  // One pivot DOF per direction, such that W_Pᵀ (b x b) is invertible and
  // well conditioned: the first b columns of Wᵀ's column-pivoted QR.
  const Eigen::MatrixXd wt = directions.transpose();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(wt);
  if (qr.rank() < b) return std::nullopt;
  std::vector<int> pivots(b);
  for (Eigen::Index j = 0; j < b; ++j) pivots[j] = static_cast<int>(qr.colsPermutation().indices()[j]);
  Eigen::MatrixXd pivot_block(b, b);
  for (Eigen::Index j = 0; j < b; ++j) pivot_block.col(j) = wt.col(pivots[j]);
  const Eigen::PartialPivLU<Eigen::MatrixXd> pivot_lu(pivot_block);
  if (!(pivot_lu.rcond() > 1e-10)) return std::nullopt;
  // y_P = Wᵀx = W_Pᵀ x_P + W_Oᵀ x_O and y_O = x_O, so E⁻¹ is the identity
  // but on the pivot rows, x_P = R y = W_Pᵀ⁻¹ (S y − W_Oᵀ y) with S the
  // pivots' selector (W_Oᵀ: Wᵀ with the pivot columns zeroed). Written
  // E⁻¹ = I + Sᵀ D, D = R − S.
  Eigen::MatrixXd selector = Eigen::MatrixXd::Zero(b, n);
  for (Eigen::Index j = 0; j < b; ++j) selector(j, pivots[j]) = 1.0;
  const Eigen::MatrixXd r = pivot_lu.solve(selector - (wt - pivot_block * selector));
  const Eigen::MatrixXd d = r - selector;
  // M_y = E⁻ᵀ M E⁻¹ by two rank-b products (O(n² b), no n x n inverse).
  Eigen::MatrixXd gathered(n, b);
  auto congruent = [&](const Eigen::MatrixXd& a) {
    Eigen::MatrixXd both = a;
    for (Eigen::Index j = 0; j < b; ++j) gathered.col(j) = a.col(pivots[j]);
    both.noalias() += gathered * d;  // A E⁻¹
    for (Eigen::Index j = 0; j < b; ++j) gathered.col(j) = both.row(pivots[j]).transpose();
    both.noalias() += d.transpose() * gathered.transpose();  // E⁻ᵀ (A E⁻¹)
    return Eigen::MatrixXd(0.5 * (both + both.transpose()));  // symmetric to rounding
  };
  LawCoordinateReduction out;
  out.reduction = reduceToInterface(congruent(mass), congruent(damping), congruent(stiffness), pivots, fast_rate,
                                    period, decay);
  InterfaceReduction& reduced = out.reduction;
  // Back to x: T = E⁻¹ T_y (T_y's pivot rows become R T_y) and P = P_y E
  // (E is the identity but on the pivot rows, which are Wᵀ).
  const Eigen::MatrixXd pivot_rows = r * reduced.basis;
  for (Eigen::Index j = 0; j < b; ++j) reduced.basis.row(pivots[j]) = pivot_rows.row(j);
  Eigen::MatrixXd pivot_columns(reduced.projection.rows(), b);
  for (Eigen::Index j = 0; j < b; ++j) {
    pivot_columns.col(j) = reduced.projection.col(pivots[j]);
    reduced.projection.col(pivots[j]).setZero();
  }
  reduced.projection.noalias() += pivot_columns * wt;
  // q's first entries are the pivots' y (reduced.boundary, sorted).
  for (int p : pivots)
    out.coordinate.push_back(static_cast<int>(std::lower_bound(reduced.boundary.begin(), reduced.boundary.end(), p) -
                                              reduced.boundary.begin()));
  return out;
}

}  // namespace eqhb
