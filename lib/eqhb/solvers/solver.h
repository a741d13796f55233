// One result type and one option set for every nonlinear solver backend.
//
// A backend implements Solver::run against a MonitoredSystem, which counts
// evaluations, enforces the evaluation and time limits, turns exceptions
// into failed evaluations and measures each equation in its own scale
// (SquareSystem::residualScales): the backend sees S⁻¹g and its Jacobian.
// Solver::solve then re-checks the returned point: "converged" is reported
// only when ‖S⁻¹g(z)‖₂ <= residual_tolerance, whatever the backend said.
// One rule for every backend: a problem and the same problem in other units
// (forces and μN times 1e-11, or 1e6) get the same verdict and iterates.
// A point within the tolerance is then asked whether its physics holds
// (SquareSystem::violatedPhysics): a residual can vanish while the law it
// stands for does not, when its equations lose their scale.
#pragma once

#include <Eigen/Dense>
#include <chrono>
#include <limits>
#include <map>
#include <string>

#include "eqhb/solvers/square_system.h"

namespace eqhb {

enum class Termination {
  kConverged,         // ‖S⁻¹g‖ <= residual_tolerance at the returned point
  kIterationLimit,    // max_iterations reached
  kEvaluationLimit,   // max_evaluations residual evaluations reached
  kTimeLimit,         // time_limit seconds reached
  kStepTolerance,     // steps became too small while ‖g‖ > tolerance
  kNotProgressing,    // no sufficient decrease over several iterations
  kEvaluationFailed,  // the residual or Jacobian was not finite / threw
  kInvalidOptions,    // options rejected before any evaluation
  kBackendError,      // the backend failed for another reason
  kLawViolated,       // ‖S⁻¹g‖ <= tolerance, yet a law grossly violated between
                      // the samples (SquareSystem::violatedPhysics): no solution
};

const char* terminationName(Termination termination);

// Dense or sparse linear algebra inside a backend (LinearAlgebra): kAuto is
// sparse when the system assembles its Jacobian sparse and has at least
// kSparseFromUnknowns unknowns (below that, dense factorisations are faster).
const char* linearAlgebraName(LinearAlgebra algebra);

struct SolverOptions {
  // Accept z when ‖S⁻¹g(z)‖₂ <= residual_tolerance, S the equations' own
  // scales (SquareSystem::residualScales; 1 for a system without). >= 0.
  double residual_tolerance = 1e-10;
  // Most iterations (trial steps or major iterations of the backend). >= 1.
  int max_iterations = 1000;
  // Most residual evaluations (Jacobian-only calls not counted). >= 1.
  int max_evaluations = 10000;
  // Wall-clock limit in seconds; 0 means none. >= 0.
  double time_limit = 0.0;
  // Backend-specific settings, "name" -> "value", passed through unchanged;
  // a backend rejects names it does not know (kInvalidOptions).
  std::map<std::string, std::string> backend;
  // Dense or sparse path (backends without a sparse variant refuse kSparse).
  LinearAlgebra linear_algebra = LinearAlgebra::kAuto;

  // False with a message naming the field, its value and the rule.
  bool isValid(std::string* why) const;
};

struct SolverResult {
  std::string solver;
  Termination termination = Termination::kBackendError;
  int native_code = 0;           // the backend's own status code
  std::string native_message;    // and its text
  double initial_norm = std::numeric_limits<double>::quiet_NaN();
  double final_norm = std::numeric_limits<double>::quiet_NaN();
  int iterations = 0;
  int residual_evaluations = 0;
  int jacobian_evaluations = 0;
  double seconds = 0.0;
  Eigen::VectorXd solution;  // the last accepted point

  bool converged() const { return termination == Termination::kConverged; }
  std::string summary() const;  // one line
};

// Counts and guards evaluations of a wrapped system for one solve.
class MonitoredSystem : public SquareSystem {
 public:
  MonitoredSystem(SquareSystem& inner, const SolverOptions& options);
  int size() const override { return inner_.size(); }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                           Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  bool nativeSparseJacobian() const override { return inner_.nativeSparseJacobian(); }
  const SparseMatrix& jacobianPattern() override { return inner_.jacobianPattern(); }
  bool residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                 Eigen::Ref<Eigen::VectorXd> g, SparseMatrix& jacobian) override;

  int residualEvaluations() const { return residual_evaluations_; }
  int jacobianEvaluations() const { return jacobian_evaluations_; }
  double firstNorm() const { return first_norm_; }
  double elapsedSeconds() const;
  bool evaluationLimitReached() const;
  bool timeLimitReached() const;
  // Evaluations (residual or Jacobian) that failed: non-finite or threw.
  int failedEvaluations() const { return failed_evaluations_; }
  // Set when an evaluation threw; the evaluation then reported failure.
  const std::string& failure() const { return failure_; }
  // 1 / s_i of the wrapped system's equations (made once per solve).
  const Eigen::VectorXd& inverseScales() const { return inverse_scales_; }

 private:
  // One evaluation, no exception let through, counted in `evaluations` (and
  // as failed unless `evaluate` succeeds with a finite g and Jacobian): g, and
  // by `scale_jacobian` the Jacobian, divided by the equations' scales; the
  // first successful residual's norm kept.
  template <class Evaluate, class ScaleJacobian>
  bool monitored(int& evaluations, const char* what, Eigen::Ref<Eigen::VectorXd> g, const Evaluate& evaluate,
                 const ScaleJacobian& scale_jacobian);
  SquareSystem& inner_;
  const SolverOptions& options_;
  std::chrono::steady_clock::time_point start_;
  int residual_evaluations_ = 0;
  int jacobian_evaluations_ = 0;
  double first_norm_ = std::numeric_limits<double>::quiet_NaN();
  int failed_evaluations_ = 0;
  std::string failure_;
  Eigen::VectorXd inverse_scales_;
};

class Solver {
 public:
  virtual ~Solver() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  // Solves system(z) = 0 from z0. Never throws for numerical trouble.
  SolverResult solve(SquareSystem& system, const Eigen::VectorXd& z0,
                     const SolverOptions& options);

 protected:
  // Fills termination, native code/message, iterations and solution (the
  // last accepted point). Counts and timing are filled in by solve().
  virtual void run(MonitoredSystem& system, const Eigen::VectorXd& z0,
                   const SolverOptions& options, SolverResult& result) = 0;
};

// Whether a backend with a sparse variant takes it for this system.
bool useSparseAlgebra(SquareSystem& system, const SolverOptions& options);
// Dense backends (n x n matrices, O(n³) factorisations) refuse systems
// larger than this: each dense matrix would pass 0.5 GB.
constexpr int kDenseMostUnknowns = 8000;
// For a backend that is dense only: false, with the reason in result
// (kInvalidOptions), when the system is too large or sparse was requested.
bool denseBackendAccepts(const std::string& backend, int unknowns, int most_unknowns,
                         const SolverOptions& options, SolverResult& result);

// Parses a backend option value; false (with why) if it is not a number.
bool parseBackendNumber(const std::string& name, const std::string& text, double* value,
                        std::string* why);

}  // namespace eqhb
