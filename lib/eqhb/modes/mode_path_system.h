// The nonlinear mode's path through (shape, ω, ξ, log a), for continuation
// in pseudo-arclength past the points where the backbone folds in amplitude
// (two modes at one amplitude: ω and ξ turn back as a grows).
//
// Unknowns y = [q; ω; ξ; s]: q = ([x̂; λ̂] − c) / a, the mode's coefficients
// per unit modal amplitude about an offset c (0, or a preload's static
// state), and s = log a (as NLvib's EPMC continuation), so that every
// unknown stays of one size over decades of amplitude. The
// equations are the mode system's (mode_system.h) at z(y) = [a q; ω; ξ],
// a = eˢ, bordered by the arclength condition
//
//   ⟨τ, y − y_pred⟩ = 0,   ⟨u, v⟩ = Σ_i w_i u_i v_i,
//
// the hyperplane through the predicted point orthogonal (in the weights w)
// to the tangent τ. The weights measure a step in units of the path's
// resolution (PathWeights); the law forces weigh nothing, being set by the
// motion. The Jacobian is the mode system's, chain-ruled:
//   ∂g/∂q = a ∂g/∂z_q,   ∂g/∂s = ∂g/∂z_q · (a q) + a ∂g/∂a,
// sparse on a pattern fixed at construction.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "eqhb/modes/mode_system.h"
#include "eqhb/solvers/square_system.h"

namespace eqhb {

// w_i = 1 / u_i² with u the change that counts as one unit of path: a tenth
// of the shape's size for each displacement and of the forces' for each law
// force, 5 % of the linear frequency for ω and ξ, one grid step of log a for
// s. A system without displacement unknowns (the condensed one) weighs its
// law forces nothing: they are zero while a contact is open, where a tenth
// of their size would make any step look infinite (damper's condensed path
// then turned back at a = 67 and retraced the backbone down to `from`).
struct PathWeights {
  Eigen::VectorXd w;
  static PathWeights at(const ModeSystem& system, const Eigen::VectorXd& y, double omega_unit, double s_unit);
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const { return (w.array() * a.array() * b.array()).sum(); }
  double norm(const Eigen::VectorXd& a) const { return std::sqrt(dot(a, a)); }
};

class ModePathSystem : public SquareSystem {
 public:
  // `offset`: c above, the mode system's coefficients (empty: 0).
  explicit ModePathSystem(ModeSystem& mode, const Eigen::VectorXd& offset = Eigen::VectorXd());
  int size() const override { return size_; }
  int sIndex() const { return size_ - 1; }

  // y of a mode-system solution z at amplitude a, and back.
  Eigen::VectorXd pathPoint(const Eigen::VectorXd& z, double amplitude) const;
  Eigen::VectorXd modePoint(const Eigen::VectorXd& y) const;

  void setConstraint(const PathWeights& weights, const Eigen::VectorXd& tangent, const Eigen::VectorXd& predicted);

  bool residual(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  bool nativeSparseJacobian() const override { return true; }
  const SparseMatrix& jacobianPattern() override { return pattern_; }
  bool residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> g,
                                 SparseMatrix& jacobian) override;
  // The mode system's scales at its current amplitude; the arclength row is
  // in path units already.
  void residualScales(Eigen::Ref<Eigen::VectorXd> scales) const override;
  std::string violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& y) override;

 private:
  bool evaluate(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> g, double* values);
  void buildPattern();
  ModeSystem& mode_;
  int inner_, size_;  // inner_: the mode system's size (q, ω, ξ)
  Eigen::VectorXd constraint_, z_, values_;  // constraint_: w ∘ τ
  Eigen::VectorXd amplitude_column_;          // the mode system's ∂g/∂a
  double constraint_at_prediction_ = 0.0;     // ⟨τ, y_pred⟩
  Eigen::VectorXd offset_;                                // c, one per coefficient
  SparseMatrix pattern_, mode_jacobian_;
  std::vector<int> mode_slot_;  // path slot of each mode-Jacobian value
  int s_column_ = 0, constraint_row_slot_ = 0;
  std::vector<int> row_slots_;  // per column: the slot of the arclength row
};

}  // namespace eqhb
