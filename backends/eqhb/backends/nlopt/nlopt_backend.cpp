#include "eqhb/backends/nlopt/nlopt_backend.h"

#include <nlopt.h>

namespace eqhb {

namespace {

struct Context {
  MonitoredSystem* system;
  const SolverOptions* options;
  nlopt_opt opt;
  Eigen::VectorXd g;
  Eigen::MatrixXd j;       // dense path
  SparseMatrix sparse_j;   // sparse path: the system's pattern
  bool sparse = false;
  Termination forced = Termination::kBackendError;
  int calls = 0;
};

// NLopt is a C library: nothing may throw through here (MonitoredSystem
// already turns exceptions into failed evaluations).
double objective(unsigned n, const double* x, double* gradient, void* data) noexcept {
  auto& ctx = *static_cast<Context*>(data);
  ++ctx.calls;
  Eigen::Map<const Eigen::VectorXd> z(x, n);
  const bool ok = !gradient     ? ctx.system->residual(z, ctx.g)
                  : ctx.sparse ? ctx.system->residualAndSparseJacobian(z, ctx.g, ctx.sparse_j)
                               : ctx.system->residualAndJacobian(z, ctx.g, ctx.j);
  if (!ok) {
    ctx.forced = Termination::kEvaluationFailed;
    nlopt_force_stop(ctx.opt);
    return HUGE_VAL;
  }
  if (ctx.system->timeLimitReached()) {
    ctx.forced = Termination::kTimeLimit;
    nlopt_force_stop(ctx.opt);
  }
  if (gradient && ctx.sparse)
    Eigen::Map<Eigen::VectorXd>(gradient, n).noalias() = ctx.sparse_j.transpose() * ctx.g;
  else if (gradient)
    Eigen::Map<Eigen::VectorXd>(gradient, n).noalias() = ctx.j.transpose() * ctx.g;
  return 0.5 * ctx.g.squaredNorm();
}

}  // namespace

Termination nloptTermination(int code) {
  switch (static_cast<nlopt_result>(code)) {
    case NLOPT_SUCCESS: return Termination::kConverged;
    case NLOPT_STOPVAL_REACHED: return Termination::kConverged;
    case NLOPT_FTOL_REACHED: return Termination::kStepTolerance;
    case NLOPT_XTOL_REACHED: return Termination::kStepTolerance;
    case NLOPT_MAXEVAL_REACHED: return Termination::kEvaluationLimit;
    case NLOPT_MAXTIME_REACHED: return Termination::kTimeLimit;
    case NLOPT_ROUNDOFF_LIMITED: return Termination::kNotProgressing;
    case NLOPT_INVALID_ARGS: return Termination::kInvalidOptions;
    case NLOPT_FORCED_STOP: return Termination::kBackendError;  // refined by the callback's reason
    case NLOPT_FAILURE:
    case NLOPT_OUT_OF_MEMORY:
    default: return Termination::kBackendError;
  }
}

namespace {
// Name and description of each method, in NloptMethod's order.
const SolverVariant kMethods[] = {
    {"nlopt-lbfgs", "NLopt LD_LBFGS on min 1/2|g|^2 with gradient J^T g"},
    {"nlopt-slsqp", "NLopt LD_SLSQP on min 1/2|g|^2 with gradient J^T g"},
    {"nlopt-newuoa", "NLopt LN_NEWUOA (derivative-free) on min 1/2|g|^2, dense, <= 200 unknowns"},
};
}  // namespace

NloptBackend::NloptBackend(NloptMethod method) : NamedSolver(kMethods[static_cast<int>(method)]), method_(method) {}

void NloptBackend::run(MonitoredSystem& system, const Eigen::VectorXd& z0,
                       const SolverOptions& options, SolverResult& result) {
  const int n = system.size();
  double initial_step = 1.0;
  for (const auto& [key, text] : options.backend) {
    std::string why;
    if (key == "initial_step" && method_ == NloptMethod::kNewuoa &&
        parseBackendNumber(key, text, &initial_step, &why) && initial_step > 0.0)
      continue;
    result.termination = Termination::kInvalidOptions;
    result.native_message = "unknown or invalid nlopt option \"" + key + "\" = \"" + text +
                            "\" (known: initial_step > 0 for nlopt-newuoa)";
    return;
  }
  // NEWUOA (quadratic models in n unknowns) and SLSQP (dense BFGS matrix
  // and QP) are dense; L-BFGS needs only Jᵀ g, sparse for large systems.
  if (method_ == NloptMethod::kNewuoa &&
      !denseBackendAccepts(name(), n, kNewuoaMostUnknowns, options, result))
    return;
  if (method_ == NloptMethod::kSlsqp &&
      !denseBackendAccepts(name(), n, kSlsqpMostUnknowns, options, result))
    return;
  const bool sparse = method_ == NloptMethod::kLbfgs && useSparseAlgebra(system, options);
  if (method_ == NloptMethod::kLbfgs && !sparse &&
      !denseBackendAccepts(name() + " (dense Jacobian)", n, kDenseMostUnknowns, options, result))
    return;
  const nlopt_algorithm algorithm = method_ == NloptMethod::kLbfgs   ? NLOPT_LD_LBFGS
                                    : method_ == NloptMethod::kSlsqp ? NLOPT_LD_SLSQP
                                                                     : NLOPT_LN_NEWUOA;
  nlopt_opt opt = nlopt_create(algorithm, n);
  if (!opt) {
    result.termination = Termination::kBackendError;
    result.native_message = "nlopt_create failed";
    return;
  }
  Context ctx{&system,
              &options,
              opt,
              Eigen::VectorXd(n),
              sparse || method_ == NloptMethod::kNewuoa ? Eigen::MatrixXd() : Eigen::MatrixXd(n, n),
              sparse ? system.jacobianPattern() : SparseMatrix(),
              sparse,
              Termination::kBackendError,
              0};
  nlopt_set_min_objective(opt, objective, &ctx);
  nlopt_set_stopval(opt, 0.5 * options.residual_tolerance * options.residual_tolerance);
  nlopt_set_maxeval(opt, options.max_evaluations);
  nlopt_set_ftol_rel(opt, 1e-15);
  nlopt_set_xtol_rel(opt, 1e-15);
  if (options.time_limit > 0.0) nlopt_set_maxtime(opt, options.time_limit);
  if (method_ == NloptMethod::kNewuoa) nlopt_set_initial_step1(opt, initial_step);

  Eigen::VectorXd z = z0;
  double f = 0.0;
  const nlopt_result status = nlopt_optimize(opt, z.data(), &f);
  nlopt_destroy(opt);
  result.native_code = static_cast<int>(status);
  result.native_message = std::string(nlopt_result_to_string(status)) +
                          (sparse ? " (sparse Jacobian)" : "");
  result.termination = nloptTermination(status);
  if (status == NLOPT_FORCED_STOP) result.termination = ctx.forced;
  result.iterations = ctx.calls;
  result.solution = z;
}

}  // namespace eqhb
