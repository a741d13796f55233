#include "eqhb/backends/ceres/ceres_backend.h"

#include <ceres/ceres.h>

namespace eqhb {

namespace {

class SystemCost : public ceres::CostFunction {
 public:
  explicit SystemCost(MonitoredSystem& system)
      : system_(system), jacobian_(system.size(), system.size()) {
    set_num_residuals(system.size());
    mutable_parameter_block_sizes()->push_back(system.size());
  }
  // Ceres calls this from its own loop: failures are reported as false
  // (MonitoredSystem already turned exceptions into failures).
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int n = system_.size();
    Eigen::Map<const Eigen::VectorXd> z(parameters[0], n);
    Eigen::Map<Eigen::VectorXd> g(residuals, n);
    if (jacobians == nullptr || jacobians[0] == nullptr) return system_.residual(z, g);
    if (!system_.residualAndJacobian(z, g, jacobian_)) return false;
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobians[0], n, n) =
        jacobian_;
    return true;
  }

 private:
  MonitoredSystem& system_;
  mutable Eigen::MatrixXd jacobian_;
};

// Stops Ceres once ‖g‖ = sqrt(2 cost) meets the tolerance, or a limit is hit.
class Guard : public ceres::IterationCallback {
 public:
  Guard(MonitoredSystem& system, const SolverOptions& options) : system_(system), options_(options) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (std::sqrt(2.0 * summary.cost) <= options_.residual_tolerance) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    if (system_.evaluationLimitReached()) {
      reason = Termination::kEvaluationLimit;
      return ceres::SOLVER_ABORT;
    }
    if (system_.timeLimitReached()) {
      reason = Termination::kTimeLimit;
      return ceres::SOLVER_ABORT;
    }
    return ceres::SOLVER_CONTINUE;
  }
  Termination reason = Termination::kBackendError;

 private:
  MonitoredSystem& system_;
  const SolverOptions& options_;
};

}  // namespace

Termination ceresTermination(int termination_type) {
  switch (static_cast<ceres::TerminationType>(termination_type)) {
    case ceres::CONVERGENCE: return Termination::kStepTolerance;  // function/gradient/parameter tolerance
    case ceres::NO_CONVERGENCE: return Termination::kIterationLimit;
    case ceres::FAILURE: return Termination::kEvaluationFailed;
    case ceres::USER_SUCCESS: return Termination::kConverged;
    case ceres::USER_FAILURE: return Termination::kBackendError;  // refined by the guard's reason
  }
  return Termination::kBackendError;
}

std::string CeresBackend::name() const {
  switch (strategy_) {
    case CeresStrategy::kLevenbergMarquardt: return "ceres-lm";
    case CeresStrategy::kDogleg: return "ceres-dogleg";
    case CeresStrategy::kSubspaceDogleg: return "ceres-dogleg-subspace";
  }
  return "ceres";
}

std::string CeresBackend::description() const {
  switch (strategy_) {
    case CeresStrategy::kLevenbergMarquardt: return "Ceres trust region, Levenberg-Marquardt, on min 1/2|g|^2";
    case CeresStrategy::kDogleg: return "Ceres trust region, traditional dogleg, on min 1/2|g|^2";
    case CeresStrategy::kSubspaceDogleg: return "Ceres trust region, subspace dogleg, on min 1/2|g|^2";
  }
  return "";
}

void CeresBackend::run(MonitoredSystem& system, const Eigen::VectorXd& z0,
                       const SolverOptions& options, SolverResult& result) {
  // One parameter block of size n: Ceres sees a dense n x n Jacobian block.
  if (!denseBackendAccepts(name(), system.size(), kDenseMostUnknowns, options, result)) return;
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  for (const auto& [key, text] : options.backend) {
    if (key == "linear_solver" && text == "dense_qr") {
      o.linear_solver_type = ceres::DENSE_QR;
    } else if (key == "linear_solver" && text == "dense_normal_cholesky") {
      o.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    } else if (key == "linear_solver" && text == "sparse_normal_cholesky") {
      if (!ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)) {
        result.termination = Termination::kInvalidOptions;
        result.native_message = "linear_solver = sparse_normal_cholesky: this Ceres has no SuiteSparse";
        return;
      }
      o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      o.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
    } else if (key == "threads") {
      double threads = 0.0;
      std::string why;
      if (!parseBackendNumber(key, text, &threads, &why) || threads < 1.0) {
        result.termination = Termination::kInvalidOptions;
        result.native_message = "threads = " + text + ": must be an integer >= 1";
        return;
      }
      o.num_threads = static_cast<int>(threads);
    } else {
      result.termination = Termination::kInvalidOptions;
      result.native_message = "unknown or invalid ceres option \"" + key + "\" = \"" + text +
                              "\" (known: linear_solver=dense_qr|dense_normal_cholesky|"
                              "sparse_normal_cholesky, threads=N)";
      return;
    }
  }
  o.minimizer_type = ceres::TRUST_REGION;
  switch (strategy_) {
    case CeresStrategy::kLevenbergMarquardt:
      o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
      break;
    case CeresStrategy::kDogleg:
      o.trust_region_strategy_type = ceres::DOGLEG;
      o.dogleg_type = ceres::TRADITIONAL_DOGLEG;
      break;
    case CeresStrategy::kSubspaceDogleg:
      o.trust_region_strategy_type = ceres::DOGLEG;
      o.dogleg_type = ceres::SUBSPACE_DOGLEG;
      break;
  }
  o.max_num_iterations = options.max_iterations;
  if (options.time_limit > 0.0) o.max_solver_time_in_seconds = options.time_limit;
  // Ceres' own relative tests would stop far from ‖g‖ <= tol on a square
  // system; keep them at round-off level and let the guard decide.
  o.function_tolerance = 1e-16;
  o.gradient_tolerance = 1e-20;
  o.parameter_tolerance = 1e-16;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  Guard guard(system, options);
  o.callbacks.push_back(&guard);

  Eigen::VectorXd z = z0;
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(new SystemCost(system), nullptr, z.data());
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);

  result.native_code = static_cast<int>(summary.termination_type);
  result.native_message = summary.message;
  result.termination = ceresTermination(summary.termination_type);
  if (summary.termination_type == ceres::USER_FAILURE) result.termination = guard.reason;
  if (summary.termination_type == ceres::NO_CONVERGENCE && system.timeLimitReached())
    result.termination = Termination::kTimeLimit;
  result.iterations = std::max(0, static_cast<int>(summary.iterations.size()) - 1);
  result.solution = z;
}

}  // namespace eqhb
