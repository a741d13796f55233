#include "eqhb/solvers/solver.h"

#include <cmath>
#include <exception>
#include <sstream>

#include "eqhb/error.h"
#include "eqhb/option_refusal.h"

namespace eqhb {

const char* terminationName(Termination termination) {
  switch (termination) {
    case Termination::kConverged: return "converged";
    case Termination::kIterationLimit: return "iteration_limit";
    case Termination::kEvaluationLimit: return "evaluation_limit";
    case Termination::kTimeLimit: return "time_limit";
    case Termination::kStepTolerance: return "step_tolerance";
    case Termination::kNotProgressing: return "not_progressing";
    case Termination::kEvaluationFailed: return "evaluation_failed";
    case Termination::kInvalidOptions: return "invalid_options";
    case Termination::kBackendError: return "backend_error";
    case Termination::kLawViolated: return "law_violated";
  }
  return "unknown";
}

const char* linearAlgebraName(LinearAlgebra algebra) {
  switch (algebra) {
    case LinearAlgebra::kAuto: return "auto";
    case LinearAlgebra::kDense: return "dense";
    case LinearAlgebra::kSparse: return "sparse";
  }
  return "unknown";
}

bool useSparseAlgebra(SquareSystem& system, const SolverOptions& options) {
  if (options.linear_algebra == LinearAlgebra::kSparse) return true;
  if (options.linear_algebra == LinearAlgebra::kDense) return false;
  return system.nativeSparseJacobian() && system.size() >= kSparseFromUnknowns;
}

bool denseBackendAccepts(const std::string& backend, int unknowns, int most_unknowns,
                         const SolverOptions& options, SolverResult& result) {
  std::string why;
  if (options.linear_algebra == LinearAlgebra::kSparse)
    why = backend + " has no sparse variant (linear algebra \"sparse\" requested)";
  else if (unknowns > most_unknowns)
    why = backend + " is dense and refuses " + std::to_string(unknowns) + " unknowns (at most " +
          std::to_string(most_unknowns) + "); use a backend with a sparse variant (dogleg-newton, ipopt, nlopt-lbfgs)";
  if (why.empty()) return true;
  result.termination = Termination::kInvalidOptions;
  result.native_message = why;
  return false;
}

bool SolverOptions::isValid(std::string* why) const {
  if (!(residual_tolerance >= 0.0) || !std::isfinite(residual_tolerance))
    return refuseOption(why, "residual_tolerance", formatNumber(residual_tolerance), "must be finite and >= 0");
  if (max_iterations < 1)
    return refuseOption(why, "max_iterations", std::to_string(max_iterations), "must be >= 1");
  if (max_evaluations < 1)
    return refuseOption(why, "max_evaluations", std::to_string(max_evaluations), "must be >= 1");
  if (!(time_limit >= 0.0) || !std::isfinite(time_limit))
    return refuseOption(why, "time_limit", formatNumber(time_limit), "must be finite and >= 0 (0: none)");
  return true;
}

std::string SolverResult::summary() const {
  std::ostringstream out;
  out << solver << ": " << terminationName(termination) << ", |g| " << initial_norm << " -> "
      << final_norm << ", " << iterations << " iterations, " << residual_evaluations
      << " residual and " << jacobian_evaluations << " Jacobian evaluations, " << seconds << " s";
  if (!native_message.empty()) out << " [" << native_message << "]";
  return out.str();
}

MonitoredSystem::MonitoredSystem(SquareSystem& inner, const SolverOptions& options)
    : inner_(inner), options_(options), start_(std::chrono::steady_clock::now()),
      inverse_scales_(Eigen::VectorXd::Ones(inner.size())) {
  inner.residualScales(inverse_scales_);
  for (Eigen::Index i = 0; i < inverse_scales_.size(); ++i) {
    const double s = inverse_scales_[i];
    inverse_scales_[i] = s > 0.0 && std::isfinite(s) && std::isfinite(1.0 / s) ? 1.0 / s : 1.0;
  }
}

namespace {
// The evaluation's answer; an exception is a failed evaluation whose
// message is kept in `failure` (none crosses a backend's callback).
template <class Evaluate>
bool guarded(const Evaluate& evaluate, const char* what, std::string& failure) {
  try {
    return evaluate();
  } catch (const std::exception& e) {
    failure = e.what();
  } catch (...) {
    failure = std::string("unknown exception in ") + what + " evaluation";
  }
  return false;
}
}  // namespace

template <class Evaluate, class ScaleJacobian>
bool MonitoredSystem::monitored(int& evaluations, const char* what, Eigen::Ref<Eigen::VectorXd> g,
                                const Evaluate& evaluate, const ScaleJacobian& scale_jacobian) {
  const bool ok = guarded(
      [&] {
        if (!evaluate() || !g.allFinite()) return false;
        g.array() *= inverse_scales_.array();
        scale_jacobian();
        return true;
      },
      what, failure_);
  ++evaluations;
  if (!ok) ++failed_evaluations_;
  if (ok && std::isnan(first_norm_)) first_norm_ = g.norm();
  return ok;
}

bool MonitoredSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                               Eigen::Ref<Eigen::VectorXd> g) {
  return monitored(
      residual_evaluations_, "residual", g, [&] { return inner_.residual(z, g); }, [] {});
}

bool MonitoredSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                          Eigen::Ref<Eigen::VectorXd> g,
                                          Eigen::Ref<Eigen::MatrixXd> jacobian) {
  return monitored(
      jacobian_evaluations_, "Jacobian", g,
      [&] { return inner_.residualAndJacobian(z, g, jacobian) && jacobian.allFinite(); },
      [&] { jacobian.array().colwise() *= inverse_scales_.array(); });
}

bool MonitoredSystem::residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                                Eigen::Ref<Eigen::VectorXd> g,
                                                SparseMatrix& jacobian) {
  return monitored(
      jacobian_evaluations_, "Jacobian", g,
      [&] {
        return inner_.residualAndSparseJacobian(z, g, jacobian) &&
               Eigen::Map<const Eigen::VectorXd>(jacobian.valuePtr(), jacobian.nonZeros()).allFinite();
      },
      [&] {
        for (int j = 0; j < jacobian.outerSize(); ++j)
          for (SparseMatrix::InnerIterator it(jacobian, j); it; ++it) it.valueRef() *= inverse_scales_[it.row()];
      });
}

double MonitoredSystem::elapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool MonitoredSystem::evaluationLimitReached() const {
  return residual_evaluations_ >= options_.max_evaluations;
}

bool MonitoredSystem::timeLimitReached() const {
  return options_.time_limit > 0.0 && elapsedSeconds() >= options_.time_limit;
}

namespace {

// "Converged" must mean the physics holds: a residual within the tolerance
// whose law is grossly violated between its samples is reported as such.
void refuseViolatedPhysics(SquareSystem& system, SolverResult& result) {
  std::string violated;
  try {
    violated = system.violatedPhysics(result.solution);
  } catch (const std::exception& e) {
    violated = std::string("its physics could not be checked: ") + e.what();
  }
  if (violated.empty()) return;
  result.termination = Termination::kLawViolated;
  result.native_message += (result.native_message.empty() ? "" : "; ") +
                           std::string("the residual is within the tolerance but ") + violated;
}

}  // namespace

SolverResult Solver::solve(SquareSystem& system, const Eigen::VectorXd& z0,
                           const SolverOptions& options) {
  SolverResult result;
  result.solver = name();
  result.solution = z0;
  std::string why;
  if (!options.isValid(&why) || z0.size() != system.size()) {
    result.termination = Termination::kInvalidOptions;
    result.native_message = why.empty() ? "initial guess has size " + std::to_string(z0.size()) +
                                              ", the system " + std::to_string(system.size())
                                        : why;
    return result;
  }
  if (!z0.allFinite()) {
    result.termination = Termination::kInvalidOptions;
    result.native_message = "initial guess contains NaN or Inf";
    return result;
  }
  MonitoredSystem monitored(system, options);
  try {
    run(monitored, z0, options, result);
  } catch (const std::exception& e) {
    result.termination = Termination::kBackendError;
    result.native_message = e.what();
  }
  result.seconds = monitored.elapsedSeconds();
  result.residual_evaluations = monitored.residualEvaluations();
  result.jacobian_evaluations = monitored.jacobianEvaluations();
  result.initial_norm = monitored.firstNorm();
  if (!monitored.failure().empty())
    result.native_message += (result.native_message.empty() ? "" : "; ") +
                             std::string("evaluation threw: ") + monitored.failure();

  // The verdict: re-evaluate at the returned point, outside the counts.
  Eigen::VectorXd g(system.size());
  bool finite = false;
  try {
    finite = result.solution.size() == system.size() && system.residual(result.solution, g) &&
             g.allFinite();
  } catch (...) {
    finite = false;
  }
  result.final_norm =
      finite ? g.cwiseProduct(monitored.inverseScales()).norm() : std::numeric_limits<double>::quiet_NaN();
  const bool within = finite && result.final_norm <= options.residual_tolerance;
  if (within && result.termination != Termination::kInvalidOptions) {
    result.termination = Termination::kConverged;
  } else if (!within && result.termination == Termination::kConverged) {
    result.termination = Termination::kNotProgressing;
    result.native_message += (result.native_message.empty() ? "" : "; ") +
                             std::string("backend reported success above the tolerance");
  }
  // Backends that survive a failed trial evaluation (shrinking their step)
  // may end for another reason; a failed solve that met a failed
  // evaluation reports it, as the backends that stop at once do.
  if (!within && monitored.failedEvaluations() > 0 &&
      result.termination != Termination::kInvalidOptions) {
    if (result.termination != Termination::kEvaluationFailed)
      result.native_message += (result.native_message.empty() ? "" : "; ") +
                               std::to_string(monitored.failedEvaluations()) +
                               " evaluation(s) failed (non-finite residual or Jacobian)";
    result.termination = Termination::kEvaluationFailed;
  }
  if (result.converged()) refuseViolatedPhysics(system, result);
  return result;
}

bool parseBackendNumber(const std::string& name, const std::string& text, double* value,
                        std::string* why) {
  try {
    size_t used = 0;
    *value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(*value)) return true;
  } catch (...) {
  }
  if (why) *why = name + " = \"" + text + "\": must be a finite number";
  return false;
}

}  // namespace eqhb
