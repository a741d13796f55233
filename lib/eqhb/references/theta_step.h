// One step of the θ-method with the laws' local problems (Moreau–Jean), the
// step behind integrateToSteadyState (time_integrator.h): its constant
// operators are built once, and a step allocates nothing.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/references/time_integrator.h"

namespace eqhb {

class ThetaStep {
 public:
  // The iteration matrix M + hθC + h²θ²K factorised, each law's response
  // Y_l = h Ŵ⁻¹ W_l s_l (n x d_l) and the Delassus blocks W_l Y_m.
  ThetaStep(const HbModel& model, const TimeOptions& options, double h);
  // From (x, v) at time t to t + h: the free velocity, the laws' forces
  // `lambda` over the step (their local problems), then the new x and v.
  void advance(double t, Eigen::VectorXd& x, Eigen::VectorXd& v, std::vector<LocalVector>& lambda);

 private:
  void forcing(double t, Eigen::VectorXd& f) const;
  // The velocity at t + h without the laws' forces.
  void freeVelocity(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  // Exact for one law, block Gauss–Seidel for several.
  void solveLocalProblems(const Eigen::VectorXd& x, const Eigen::VectorXd& v, std::vector<LocalVector>& lambda);

  const HbModel& model_;
  const LinearStructure& s_;
  int n_, laws_;
  double h_, theta_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  std::vector<Eigen::MatrixXd> response_;
  // coupling_[l][m] = W_l Y_m (the Delassus blocks): velocity of law l's
  // components per unit force of law m.
  std::vector<std::vector<LocalMatrix>> coupling_;
  std::vector<LocalVector> lambda_start_;
  Eigen::VectorXd f0_, f1_, rhs_, v_free_, v_new_;
  StepProblem problem_;
};

}  // namespace eqhb
