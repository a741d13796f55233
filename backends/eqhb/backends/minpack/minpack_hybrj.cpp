#include "eqhb/backends/minpack/minpack_hybrj.h"

#include <cminpack.h>

#include <vector>

namespace eqhb {

namespace {

// Codes our callback returns to stop hybrj; hybrj hands them back as info.
constexpr int kStopTolerance = -1;
constexpr int kStopFailed = -2;
constexpr int kStopTime = -3;

struct CallbackContext {
  MonitoredSystem* system;
  const SolverOptions* options;
  Eigen::VectorXd accepted;  // the point that met the tolerance, if any
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd scratch;
};

int evaluate(void* data, int n, const double* x, double* fvec, double* fjac, int ldfjac,
             int iflag) noexcept {
  // Exceptions must not cross into C: MonitoredSystem already turns them
  // into failed evaluations, and nothing else here throws.
  auto& ctx = *static_cast<CallbackContext*>(data);
  Eigen::Map<const Eigen::VectorXd> z(x, n);
  if (iflag == 1) {
    Eigen::Map<Eigen::VectorXd> g(fvec, n);
    if (!ctx.system->residual(z, g)) return kStopFailed;
    if (g.norm() <= ctx.options->residual_tolerance) {
      ctx.accepted = z;
      return kStopTolerance;
    }
    if (ctx.system->timeLimitReached()) return kStopTime;
    return 0;
  }
  if (iflag == 2) {
    Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>> j(fjac, n, n, Eigen::OuterStride<>(ldfjac));
    if (!ctx.system->residualAndJacobian(z, ctx.scratch, ctx.jacobian)) return kStopFailed;
    j = ctx.jacobian;
    return 0;
  }
  return 0;
}

}  // namespace

Termination minpackTermination(int info) {
  switch (info) {
    case 0: return Termination::kInvalidOptions;
    case 1: return Termination::kStepTolerance;
    case 2: return Termination::kEvaluationLimit;
    case 3: return Termination::kStepTolerance;
    case 4: return Termination::kNotProgressing;
    case 5: return Termination::kNotProgressing;
    case kStopTolerance: return Termination::kConverged;
    case kStopFailed: return Termination::kEvaluationFailed;
    case kStopTime: return Termination::kTimeLimit;
    default: return Termination::kBackendError;
  }
}

const char* minpackMessage(int info) {
  switch (info) {
    case 0: return "improper input parameters";
    case 1: return "relative error between two consecutive iterates is at most xtol";
    case 2: return "number of calls to fcn with iflag = 1 has reached maxfev";
    case 3: return "xtol is too small: no further improvement in x is possible";
    case 4: return "iteration is not making good progress (five Jacobian evaluations)";
    case 5: return "iteration is not making good progress (ten iterations)";
    case kStopTolerance: return "stopped by the callback: residual within tolerance";
    case kStopFailed: return "stopped by the callback: evaluation failed";
    case kStopTime: return "stopped by the callback: time limit";
    default: return "unknown hybrj status";
  }
}

void MinpackHybrj::run(MonitoredSystem& system, const Eigen::VectorXd& z0,
                       const SolverOptions& options, SolverResult& result) {
  double factor = 100.0, xtol = 1e-14;
  int mode = 1;
  for (const auto& [key, text] : options.backend) {
    std::string why;
    double value = 0.0;
    if (key == "factor" || key == "xtol") {
      if (!parseBackendNumber(key, text, &value, &why) || value < 0.0 ||
          (key == "factor" && value == 0.0)) {
        result.termination = Termination::kInvalidOptions;
        result.native_message = why.empty() ? key + " = " + text + ": out of range" : why;
        return;
      }
      (key == "factor" ? factor : xtol) = value;
    } else if (key == "scaling" && (text == "columns" || text == "none")) {
      mode = text == "columns" ? 1 : 2;
    } else {
      result.termination = Termination::kInvalidOptions;
      result.native_message = "unknown or invalid minpack option \"" + key + "\" = \"" + text +
                              "\" (known: factor, xtol, scaling=columns|none)";
      return;
    }
  }
  const int n = system.size();
  if (!denseBackendAccepts(name(), n, kMinpackMostUnknowns, options, result)) return;
  CallbackContext ctx{&system, &options, Eigen::VectorXd(), Eigen::MatrixXd(n, n),
                      Eigen::VectorXd(n)};
  Eigen::VectorXd x = z0, fvec(n), diag = Eigen::VectorXd::Ones(n), qtf(n);
  Eigen::MatrixXd fjac(n, n);
  std::vector<double> r(n * (n + 1) / 2), wa(4 * n);
  int nfev = 0, njev = 0;
  const int info = hybrj(evaluate, &ctx, n, x.data(), fvec.data(), fjac.data(), n, xtol,
                         options.max_evaluations, diag.data(), mode, factor, 0, &nfev, &njev,
                         r.data(), static_cast<int>(r.size()), qtf.data(), wa.data(),
                         wa.data() + n, wa.data() + 2 * n, wa.data() + 3 * n);
  result.native_code = info;
  result.native_message = minpackMessage(info);
  result.termination = minpackTermination(info);
  result.solution = info == kStopTolerance ? ctx.accepted : x;
  result.iterations = std::max(0, nfev - 1);  // one residual evaluation per trial step
}

}  // namespace eqhb
