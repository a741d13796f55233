#include "eqhb/backends/dogleg/sparse_newton_dogleg.h"
#include "eqhb/backends/dogleg/trust_radius.h"

#include <Eigen/UmfPackSupport>
#include <cmath>
#include <limits>

namespace eqhb {

namespace {
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
}  // namespace

void runSparseNewtonDogleg(MonitoredSystem& system, const Eigen::VectorXd& z0,
                           const SolverOptions& options, const DoglegSettings& settings,
                           SolverResult& result) {
  const Eigen::Index n = system.size();
  SparseMatrix jacobian = system.jacobianPattern();
  Eigen::UmfPackLU<SparseMatrix> lu;
  bool analyzed = false;  // the symbolic analysis: once, on the first Jacobian's values
  Eigen::VectorXd z = z0, g(n), trial(n), g_trial(n), step(n), model_residual(n);
  Eigen::VectorXd newton(n), scaled_newton(n), gradient(n), direction(n), image(n), cauchy(n),
      difference(n);
  Eigen::VectorXd diag = Eigen::VectorXd::Ones(n);
  result.solution = z;

  auto finish = [&](Termination t, int code, const std::string& message) {
    result.termination = t;
    result.native_code = code;
    result.native_message = "sparse LU (UMFPACK); " + message;
    result.solution = z;
  };

  if (!system.residual(z, g))
    return finish(Termination::kEvaluationFailed, -1, "residual failed at the initial guess");
  double g_norm = g.norm();
  if (g_norm <= options.residual_tolerance)
    return finish(Termination::kConverged, 0, "initial guess within tolerance");

  double radius = 0.0, z_norm = 0.0;
  int consecutive_successes = 0;
  int slow_steps = 0, slow_jacobians = 0, singular = 0;
  bool no_success_yet = true;

  // The Jacobian's evaluation and each factorisation can take long on a
  // large system: the time limit is checked after each, saying where.
  auto out_of_time = [&](const char* after) {
    if (!system.timeLimitReached()) return false;
    finish(Termination::kTimeLimit, 7,
           std::string("time limit reached after the ") + after + " of iteration " +
               std::to_string(result.iterations + 1));
    return true;
  };
  if (out_of_time("initial residual")) return;

  while (true) {
    // ---- Jacobian, scaling, and the two directions of this model
    if (!system.residualAndSparseJacobian(z, g, jacobian))
      return finish(Termination::kEvaluationFailed, -1, "Jacobian evaluation failed");
    if (out_of_time("Jacobian evaluation")) return;
    g_norm = g.norm();
    if (settings.scale_columns) {
      for (Eigen::Index j = 0; j < n; ++j) {
        const double norm = jacobian.col(j).norm();
        const double scale = norm == 0.0 ? 1.0 : norm;
        diag[j] = no_success_yet ? scale : std::max(diag[j], scale);
      }
    }
    if (no_success_yet) {
      z_norm = diag.cwiseProduct(z).norm();
      radius = z_norm > 0.0 ? settings.factor * z_norm : settings.factor;
    }
    // Gauss–Newton step; a singular J leaves only the gradient direction.
    if (!analyzed) {
      lu.analyzePattern(jacobian);
      analyzed = true;
      if (out_of_time("symbolic factorisation")) return;
    }
    lu.factorize(jacobian);
    if (out_of_time("numeric factorisation")) return;
    bool have_newton = lu.info() == Eigen::Success;
    if (have_newton) {
      newton = lu.solve(g);
      newton = -newton;
      have_newton = lu.info() == Eigen::Success && newton.allFinite();
    }
    if (!have_newton) ++singular;
    scaled_newton = diag.cwiseProduct(newton);
    const double newton_norm = have_newton ? scaled_newton.norm() : 0.0;
    // Steepest descent of ½‖g + J p‖² in scaled variables: −D⁻¹ Jᵀ g.
    gradient.noalias() = jacobian.transpose() * g;
    gradient.array() /= diag.array();
    const double gradient_norm = gradient.norm();
    double cauchy_length = std::numeric_limits<double>::infinity();
    if (gradient_norm > 0.0) {
      direction = -(gradient / gradient_norm);
      image.noalias() = jacobian * direction.cwiseQuotient(diag);
      const double curvature = image.norm();
      if (curvature > 0.0) cauchy_length = gradient_norm / (curvature * curvature);
    }
    if (!have_newton && gradient_norm == 0.0)
      return finish(Termination::kNotProgressing, 4, "singular Jacobian with zero gradient");
    bool fresh_jacobian = true;

    // ---- trust-region steps on this model
    while (true) {
      if (result.iterations >= options.max_iterations)
        return finish(Termination::kIterationLimit, 6, "iteration limit");
      ++result.iterations;
      // Dogleg in scaled variables y = D p inside ‖y‖ <= radius.
      if (have_newton && newton_norm <= radius) {
        step = newton;
      } else if (gradient_norm == 0.0) {
        step = newton * (radius / newton_norm);
      } else if (!have_newton || cauchy_length >= radius) {
        step = (std::min(radius, cauchy_length) * direction).cwiseQuotient(diag);
      } else {
        cauchy = cauchy_length * direction;
        difference = scaled_newton - cauchy;
        const double a = difference.squaredNorm();
        const double b = cauchy.dot(difference);
        const double c = cauchy.squaredNorm() - radius * radius;  // < 0
        const double root = std::sqrt(b * b - a * c);
        const double tau = b > 0.0 ? -c / (b + root) : (root - b) / a;
        step = (cauchy + tau * difference).cwiseQuotient(diag);
      }
      const double step_norm = diag.cwiseProduct(step).norm();
      if (no_success_yet) radius = std::min(radius, step_norm);

      trial = z + step;
      if (!system.residual(trial, g_trial))
        return finish(Termination::kEvaluationFailed, -1, "residual evaluation failed");
      const double trial_norm = g_trial.norm();
      const double actual = trial_norm < g_norm ? 1.0 - std::pow(trial_norm / g_norm, 2) : -1.0;
      model_residual.noalias() = jacobian * step;
      model_residual += g;
      const double model_norm = model_residual.norm();
      const double predicted = model_norm < g_norm ? 1.0 - std::pow(model_norm / g_norm, 2) : 0.0;
      const double ratio = predicted > 0.0 ? actual / predicted : 0.0;

      dogleg::updateTrustRadius(ratio, step_norm, radius, consecutive_successes);
      const bool accepted = ratio >= 1e-4;
      if (accepted) {
        no_success_yet = false;
        z = trial;
        g = g_trial;
        z_norm = diag.cwiseProduct(z).norm();
        g_norm = trial_norm;
        result.solution = z;
      }
      ++slow_steps;
      if (actual >= 1e-3) slow_steps = 0;
      if (fresh_jacobian) ++slow_jacobians;
      if (actual >= 0.1) slow_jacobians = 0;

      const std::string note =
          singular > 0 ? " (" + std::to_string(singular) + " singular Jacobian(s): gradient steps)" : "";
      if (g_norm <= options.residual_tolerance)
        return finish(Termination::kConverged, 0, "residual within tolerance" + note);
      if (radius <= settings.xtol * z_norm || g_norm == 0.0)
        return finish(Termination::kStepTolerance, 1, "trust radius below xtol relative to |D z|" + note);
      if (system.evaluationLimitReached())
        return finish(Termination::kEvaluationLimit, 2, "evaluation limit" + note);
      if (system.timeLimitReached()) return finish(Termination::kTimeLimit, 7, "time limit" + note);
      if (0.1 * std::max(0.1 * radius, step_norm) <= kEpsilon * z_norm)
        return finish(Termination::kStepTolerance, 3, "steps below machine precision" + note);
      if (slow_jacobians == 5)
        return finish(Termination::kNotProgressing, 4,
                      "no progress over the last five Jacobian evaluations" + note);
      if (slow_steps == 10)
        return finish(Termination::kNotProgressing, 5, "no progress over the last ten iterations" + note);
      if (accepted) break;  // new iterate: new weak Jacobian
      fresh_jacobian = false;
    }
  }
}

}  // namespace eqhb
