// How a law of dimension d sits on a structure of n DOFs: a sparse d x n map
// W. Component a of the law reads u_a = Σ_j W_aj x_j, and the law's force
// acts on the structure as Wᵀ (forceSign · λ) (spec §1: the same W in the
// kinematics and in the dynamics keeps the coupling symmetric).
//
// Grounded along an axis (one DOF against the ground, today's `dofs = [i]`)
// is a unit row W_a = e_i. A relative element between nodes p and q along a
// unit direction n has W_a = nᵀ on p's DOFs and −nᵀ on q's: its force is equal
// and opposite on the two nodes.
#pragma once

#include <Eigen/Dense>
#include <initializer_list>
#include <string>
#include <vector>

namespace eqhb {

struct AttachmentTerm {
  int dof;        // 0-based DOF of the structure
  double weight;  // W_a,dof
};

class LawAttachment {
 public:
  LawAttachment() = default;
  // Grounded: component a is x[dofs[a]] (0-based), the force acts on that DOF.
  LawAttachment(std::vector<int> dofs);  // NOLINT: a DOF list is the grounded form
  LawAttachment(std::initializer_list<int> dofs) : LawAttachment(std::vector<int>(dofs)) {}  // NOLINT
  // A general map: rows[a] lists the nonzero W_a,j (each DOF once per row).
  explicit LawAttachment(std::vector<std::vector<AttachmentTerm>> rows);

  // An element between nodes p and q, each given by its DOFs along the
  // spatial axes (q empty: against the ground): component a reads
  // directions[a] · (u_p − u_q). Zero weights are left out, so an axis
  // direction against the ground is the grounded form. The directions are
  // taken as given (the scene reader checks and normalises them).
  static LawAttachment relative(const std::vector<int>& p, const std::vector<int>& q,
                                const std::vector<Eigen::VectorXd>& directions);

  int dimension() const { return static_cast<int>(rows_.size()); }
  const std::vector<AttachmentTerm>& row(int a) const { return rows_[a]; }
  // True when every row is one DOF with weight exactly 1 (grounded along an
  // axis): the consumers that need one DOF per component ask this first.
  bool grounded() const { return grounded_; }
  // The DOF of component a of a grounded attachment (see grounded()).
  int dof(int a) const { return rows_[a].front().dof; }
  // Every DOF the map touches, once each, in order of first appearance.
  const std::vector<int>& dofs() const { return dofs_; }
  // "[3, 5]" (1-based) for grounded, else the rows with their weights.
  std::string describe() const;

  // u_a = Σ_j W_aj x[j] for a vector of DOF values.
  template <class Vector>
  double gather(const Vector& x, int a) const {
    const auto& r = rows_[a];
    double u = r.front().weight * x[r.front().dof];
    for (size_t k = 1; k < r.size(); ++k) u += r[k].weight * x[r[k].dof];
    return u;
  }
  // The same on coefficient vectors laid out DOF by DOF (`stride` values
  // each, DOF j at x + j * stride): out[0..stride) = Σ_j W_aj x_j. No
  // allocation: out is the caller's.
  void gatherCoefficients(const double* x, int stride, int a, double* out) const;
  // y_j += scale · W_aj · values for every DOF j of row a (same layout).
  void scatterCoefficients(const double* values, int stride, int a, double scale, double* y) const;
  // Wᵀ as a dense n x d matrix, each column times `scale` (the force sign).
  Eigen::MatrixXd transposeDense(int n, double scale = 1.0) const;
  // W · Y for a dense n x m matrix Y: row a of the d x m result (the
  // Delassus coupling W M̂⁻¹ Wᵀ when Y = M̂⁻¹ Wᵀ).
  Eigen::RowVectorXd rowTimes(const Eigen::MatrixXd& y, int a) const;
  // Throws InputError naming `field` when a DOF is outside 0..n-1, a row is
  // empty, a weight is not finite, or a grounded DOF is listed twice.
  void validate(int n, const std::string& field) const;

 private:
  void index();
  std::vector<std::vector<AttachmentTerm>> rows_;
  std::vector<int> dofs_;
  bool grounded_ = true;
};

}  // namespace eqhb
