#include "eqhb/backends/ceres/ceres_backend.h"

#include <ceres/ceres.h>
#include <ceres/evaluation_callback.h>

#include <memory>
#include <vector>

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

// The sparse path. Ceres derives the sparsity of the Jacobian from the block
// structure of the problem, not from a matrix: every unknown is its own
// parameter block and every equation its own residual block, which depends
// on exactly the unknowns of its row of the system's Jacobian pattern. The
// system is evaluated once per point (residual, or residual and sparse
// Jacobian) in PrepareForEvaluation, before Ceres asks the row blocks, which
// only copy their entries out; Ceres then assembles the compressed-row
// Jacobian and factors JᵀJ with SuiteSparse (SPARSE_NORMAL_CHOLESKY).
class SharedEvaluation : public ceres::EvaluationCallback {
 public:
  SharedEvaluation(MonitoredSystem& system, const Eigen::VectorXd& z)
      : system_(system), z_(z), g_(system.size()), jacobian_(system.jacobianPattern()) {}
  void PrepareForEvaluation(bool evaluate_jacobians, bool new_evaluation_point) override {
    // Ceres has written the point into z_ (the user's parameter blocks).
    if (!new_evaluation_point && (!evaluate_jacobians || have_jacobian_)) return;
    have_jacobian_ = evaluate_jacobians;
    ok_ = evaluate_jacobians ? system_.residualAndSparseJacobian(z_, g_, jacobian_) : system_.residual(z_, g_);
  }
  bool ok() const { return ok_; }
  double residual(int row) const { return g_[row]; }
  double entry(int index) const { return jacobian_.valuePtr()[index]; }

 private:
  MonitoredSystem& system_;
  const Eigen::VectorXd& z_;
  Eigen::VectorXd g_;
  SparseMatrix jacobian_;  // the pattern's copy; values overwritten
  bool ok_ = false, have_jacobian_ = false;
};

// Row `row` of g(z) = 0 as a residual block over the unknowns of its pattern;
// slots_[k] is the entry of the k-th of them in the sparse Jacobian's values
// (−1: an equation on no unknown, given one block with a zero derivative).
class RowCost : public ceres::CostFunction {
 public:
  RowCost(const SharedEvaluation& shared, int row, std::vector<int> slots)
      : shared_(shared), row_(row), slots_(std::move(slots)) {
    set_num_residuals(1);
    for (size_t k = 0; k < slots_.size(); ++k) mutable_parameter_block_sizes()->push_back(1);
  }
  bool Evaluate(double const* const*, double* residuals, double** jacobians) const override {
    if (!shared_.ok()) return false;
    residuals[0] = shared_.residual(row_);
    if (jacobians == nullptr) return true;
    for (size_t k = 0; k < slots_.size(); ++k)
      if (jacobians[k] != nullptr) jacobians[k][0] = slots_[k] < 0 ? 0.0 : shared_.entry(slots_[k]);
    return true;
  }

 private:
  const SharedEvaluation& shared_;
  int row_;
  std::vector<int> slots_;
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

namespace {
// Name and description of each strategy, in CeresStrategy's order.
const SolverVariant kStrategies[] = {
    {"ceres-lm", "Ceres trust region, Levenberg-Marquardt, on min 1/2|g|^2"},
    {"ceres-dogleg", "Ceres trust region, traditional dogleg, on min 1/2|g|^2"},
    {"ceres-dogleg-subspace", "Ceres trust region, subspace dogleg, on min 1/2|g|^2"},
};
}  // namespace

CeresBackend::CeresBackend(CeresStrategy strategy)
    : NamedSolver(kStrategies[static_cast<int>(strategy)]), strategy_(strategy) {}

void CeresBackend::run(MonitoredSystem& system, const Eigen::VectorXd& z0,
                       const SolverOptions& options, SolverResult& result) {
  // Dense: one parameter block of size n, a dense n x n Jacobian block.
  // Sparse: one block per unknown and per equation (see RowCost).
  const bool sparse = useSparseAlgebra(system, options);
  const bool have_suitesparse = ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE);
  if (sparse && !have_suitesparse) {
    result.termination = Termination::kInvalidOptions;
    result.native_message = name() + ": the sparse path needs SuiteSparse, which this Ceres lacks";
    return;
  }
  if (!sparse && !denseBackendAccepts(name(), system.size(), kDenseMostUnknowns, options, result)) return;
  ceres::Solver::Options o;
  o.linear_solver_type = sparse ? ceres::SPARSE_NORMAL_CHOLESKY : ceres::DENSE_QR;
  o.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  for (const auto& [key, text] : options.backend) {
    if (sparse && key == "linear_solver" && text != "sparse_normal_cholesky") {
      result.termination = Termination::kInvalidOptions;
      result.native_message = "linear_solver = " + text +
                              ": the sparse path (sparse Jacobian) takes only sparse_normal_cholesky";
      return;
    } else if (key == "linear_solver" && text == "dense_qr") {
      o.linear_solver_type = ceres::DENSE_QR;
    } else if (key == "linear_solver" && text == "dense_normal_cholesky") {
      o.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    } else if (key == "linear_solver" && text == "sparse_normal_cholesky") {
      if (!have_suitesparse) {
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
  std::unique_ptr<SharedEvaluation> shared;
  if (sparse) {
    shared = std::make_unique<SharedEvaluation>(system, z);
    problem_options.evaluation_callback = shared.get();
  }
  ceres::Problem problem(problem_options);
  if (sparse) {
    // Rows of the column-major pattern: (column, value slot) per row.
    const SparseMatrix& pattern = system.jacobianPattern();
    std::vector<std::vector<std::pair<int, int>>> rows(pattern.rows());
    for (int j = 0; j < pattern.outerSize(); ++j)
      for (int p = pattern.outerIndexPtr()[j]; p < pattern.outerIndexPtr()[j + 1]; ++p)
        rows[pattern.innerIndexPtr()[p]].emplace_back(j, p);
    std::vector<double*> blocks;
    std::vector<int> slots;
    for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
      blocks.clear();
      slots.clear();
      for (const auto& [column, slot] : rows[i]) {
        blocks.push_back(z.data() + column);
        slots.push_back(slot);
      }
      if (blocks.empty()) {  // an equation on no unknown: its residual still counts
        blocks.push_back(z.data() + i);
        slots.push_back(-1);
      }
      problem.AddResidualBlock(new RowCost(*shared, i, slots), nullptr, blocks);
    }
    for (int j = 0; j < system.size(); ++j)  // unknowns no equation uses
      if (!problem.HasParameterBlock(z.data() + j)) problem.AddParameterBlock(z.data() + j, 1);
  } else {
    problem.AddResidualBlock(new SystemCost(system), nullptr, z.data());
  }
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);

  result.native_code = static_cast<int>(summary.termination_type);
  result.native_message = summary.message;
  if (sparse) result.native_message += " (sparse Jacobian, SPARSE_NORMAL_CHOLESKY on SuiteSparse)";
  result.termination = ceresTermination(summary.termination_type);
  if (summary.termination_type == ceres::USER_FAILURE) result.termination = guard.reason;
  if (summary.termination_type == ceres::NO_CONVERGENCE && system.timeLimitReached())
    result.termination = Termination::kTimeLimit;
  result.iterations = std::max(0, static_cast<int>(summary.iterations.size()) - 1);
  result.solution = z;
}

}  // namespace eqhb
