// The Moré–Garbow–Hillstrom nonlinear-equation test problems (J. J. Moré,
// B. S. Garbow, K. E. Hillstrom, "Testing unconstrained optimization
// software", ACM TOMS 7(1), 1981; the 14 square systems MINPACK's hybrj was
// tested on), with exact Jacobians by forward-mode automatic differentiation,
// and the comparison of two solvers over every problem and start.
#pragma once

#include <map>

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "eqhb/solvers/solver.h"
#include "eqhb/solvers/square_system.h"

namespace eqhb::mgh {

// Problem numbers 1..14 as in MINPACK's test drivers.
std::string problemName(int problem);
// The standard starting point times `factor` (problem 6, Watson, starts at
// zero: its multiples are the constant vector `factor`).
Eigen::VectorXd startingPoint(int problem, int n, double factor);

class MghSystem : public SquareSystem {
 public:
  MghSystem(int problem, int n);
  int size() const override { return n_; }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                           Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;

 private:
  int problem_, n_;
};

struct Case {
  int problem;
  int n;
  double factor;
};
// The (problem, dimension) pairs of MINPACK's hybrj test driver, each with
// the starts ×1, ×10 and ×100: 66 cases.
std::vector<Case> standardCases();

// A case counts as solved when the returned point has ‖f‖₂ <= this.
constexpr double kSolvedNorm = 1e-6;

struct Outcome {
  bool solved = false;
  std::string termination;
  int native_code = 0;
  int residual_evaluations = 0;
  int jacobian_evaluations = 0;
  double final_norm = 0.0;
};
struct Row {
  Case test;
  Outcome own, reference;
};

// Runs both solvers with MINPACK hybrj1's settings (xtol = sqrt(eps),
// maxfev = 100(n+1), factor 100, column scaling, no residual stop).
// `own_backend` and `reference_backend` add backend options (e.g. the
// dogleg's factorisation) to each solver's.
std::vector<Row> compare(Solver& own, Solver& reference, const std::vector<Case>& cases,
                         const std::map<std::string, std::string>& own_backend = {},
                         const std::map<std::string, std::string>& reference_backend = {});
// Markdown table of the rows plus a totals line.
std::string markdownTable(const std::vector<Row>& rows);

}  // namespace eqhb::mgh
