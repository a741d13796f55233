#include "eqhb/references/theta_step.h"

#include <algorithm>

namespace eqhb {

ThetaStep::ThetaStep(const HbModel& model, const TimeOptions& options, double h)
    : model_(model),
      s_(model.structure),
      n_(model.structure.dofs()),
      laws_(static_cast<int>(model.laws.size())),
      h_(h),
      theta_(options.theta),
      lu_(Eigen::MatrixXd(s_.mass + h * theta_ * s_.damping + h * h * theta_ * theta_ * s_.stiffness)),
      response_(laws_),
      coupling_(laws_, std::vector<LocalMatrix>(laws_)),
      f0_(n_),
      f1_(n_),
      rhs_(n_),
      v_free_(n_),
      v_new_(n_) {
  for (int l = 0; l < laws_; ++l) {
    const auto& attached = model.laws[l];
    response_[l] = h * lu_.solve(attached.attachment.transposeDense(n_, attached.law->forceSign()));
  }
  for (int l = 0; l < laws_; ++l)
    for (int m = 0; m < laws_; ++m) {
      const int dl = model.laws[l].law->dimension(), dm = model.laws[m].law->dimension();
      coupling_[l][m].resize(dl, dm);
      for (int a = 0; a < dl; ++a) coupling_[l][m].row(a) = model.laws[l].attachment.rowTimes(response_[m], a);
    }
  for (int l = 0; l < laws_; ++l) lambda_start_.push_back(LocalVector::Zero(model.laws[l].law->dimension()));
  problem_.h = h;
  problem_.theta = theta_;
  problem_.restitution = options.restitution;
}

void ThetaStep::forcing(double t, Eigen::VectorXd& f) const {
  f.setZero();
  for (const auto& load : s_.loads) f[load.dof] += load.at(model_.omega * t);
}

void ThetaStep::advance(double t, Eigen::VectorXd& x, Eigen::VectorXd& v, std::vector<LocalVector>& lambda) {
  const double h = h_, theta = theta_;
  freeVelocity(t, x, v);
  solveLocalProblems(x, v, lambda);
  v_new_ = v_free_;
  for (int l = 0; l < laws_; ++l) v_new_.noalias() += response_[l] * lambda[l];
  x += h * (theta * v_new_ + (1.0 - theta) * v);
  v = v_new_;
}

void ThetaStep::freeVelocity(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  const double h = h_, theta = theta_;
  forcing(t, f0_);
  forcing(t + h, f1_);
  rhs_.noalias() = s_.mass * v;
  rhs_ += h * (theta * f1_ + (1.0 - theta) * f0_);
  rhs_.noalias() -= h * (1.0 - theta) * (s_.damping * v);
  rhs_.noalias() -= h * (s_.stiffness * x);
  rhs_.noalias() -= h * h * theta * (1.0 - theta) * (s_.stiffness * v);
  v_free_ = lu_.solve(rhs_);
}

void ThetaStep::solveLocalProblems(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                   std::vector<LocalVector>& lambda) {
  lambda_start_ = lambda;  // internal states (a slider) start from the previous step
  const int sweeps = laws_ > 1 ? 100 : 1;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    double change = 0.0;
    for (int l = 0; l < laws_; ++l) {
      const auto& attached = model_.laws[l];
      const int d = attached.law->dimension();
      problem_.x_start.resize(d);
      problem_.v_start.resize(d);
      problem_.u_free.resize(d);
      for (int a = 0; a < d; ++a) {
        problem_.x_start[a] = attached.attachment.gather(x, a);
        problem_.v_start[a] = attached.attachment.gather(v, a);
        problem_.u_free[a] = attached.attachment.gather(v_free_, a);
      }
      for (int m = 0; m < laws_; ++m)
        if (m != l) problem_.u_free += coupling_[l][m] * lambda[m];
      problem_.delassus = coupling_[l][l];
      problem_.force_start = lambda_start_[l];
      const LocalVector next = attached.law->solveStep(problem_);
      change = std::max(change, (next - lambda[l]).cwiseAbs().maxCoeff());
      lambda[l] = next;
    }
    if (change <= 1e-14) break;
  }
}

}  // namespace eqhb
