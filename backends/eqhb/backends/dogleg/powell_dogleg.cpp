#include "eqhb/backends/dogleg/powell_dogleg.h"
#include "eqhb/backends/dogleg/trust_radius.h"

#include "eqhb/backends/dogleg/sparse_newton_dogleg.h"

#include <cmath>
#include <limits>

namespace eqhb {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// Rotation (c, s) with [c s; −s c] (a, b)ᵀ = (h, 0)ᵀ, h = √(a² + b²) > 0,
// returned. The rotations of an update form a chain (each needs the last
// one's h or rotated diagonal), so their latency counts: within the range
// where a² + b² neither overflows nor underflows, one square root and one
// division; outside it the ratio of the smaller to the larger magnitude
// keeps the square finite. std::hypot's correctly rounded result is not
// needed here and costs several times more.
double givens(double a, double b, double* c, double* s) {
  if (b == 0.0) {
    *c = 1.0;
    *s = 0.0;
    return a;
  }
  const double squares = a * a + b * b;
  double h;
  if (squares > std::numeric_limits<double>::min() && squares < std::numeric_limits<double>::infinity()) {
    h = std::sqrt(squares);
  } else {
    const double abs_a = std::abs(a), abs_b = std::abs(b);
    const double large = std::max(abs_a, abs_b), small = std::min(abs_a, abs_b);
    const double t = small / large;
    h = large * std::sqrt(1.0 + t * t);
  }
  const double inverse = 1.0 / h;
  *c = a * inverse;
  *s = b * inverse;
  return h;
}

// Contiguous columns (of Q): a plain loop the compiler vectorises.
void rotateColumns(double* __restrict x, double* __restrict y, Eigen::Index n, double c, double s) {
  for (Eigen::Index k = 0; k < n; ++k) {
    const double xi = x[k], yi = y[k];
    x[k] = c * xi + s * yi;
    y[k] = -s * xi + c * yi;
  }
}

// Rows of the column-major R, `stride` apart: a plain pointer loop (Eigen's
// row blocks cost several times the arithmetic at n = 20).
void rotateRows(double* x, double* y, Eigen::Index n, Eigen::Index stride, double c, double s) {
  for (Eigen::Index k = 0; k < n * stride; k += stride) {
    const double xi = x[k], yi = y[k];
    x[k] = c * xi + s * yi;
    y[k] = -s * xi + c * yi;
  }
}

using Settings = DoglegSettings;

bool parseSettings(const SolverOptions& options, Settings* settings, std::string* why) {
  for (const auto& [key, text] : options.backend) {
    double value = 0.0;
    if (key == "factor") {
      if (!parseBackendNumber(key, text, &value, why)) return false;
      if (!(value > 0.0)) {
        *why = "factor = " + text + ": must be > 0";
        return false;
      }
      settings->factor = value;
    } else if (key == "xtol") {
      if (!parseBackendNumber(key, text, &value, why)) return false;
      if (!(value >= 0.0)) {
        *why = "xtol = " + text + ": must be >= 0";
        return false;
      }
      settings->xtol = value;
    } else if (key == "scaling") {
      if (text != "columns" && text != "none") {
        *why = "scaling = \"" + text + "\": must be \"columns\" or \"none\"";
        return false;
      }
      settings->scale_columns = text == "columns";
    } else {
      *why = "unknown dogleg option \"" + key + "\" (known: factor, xtol, scaling)";
      return false;
    }
  }
  return true;
}

}  // namespace

std::string PowellDogleg::name() const {
  return policy_ == JacobianPolicy::kBroyden ? "dogleg" : "dogleg-newton";
}

std::string PowellDogleg::description() const {
  return policy_ == JacobianPolicy::kBroyden
             ? "own Powell hybrid dogleg (hybrj class): Broyden updates between weak Jacobians"
             : "own Powell dogleg with the weak Jacobian at every iterate (Newton-dogleg)";
}

void doglegStep(const Eigen::MatrixXd& r, const Eigen::VectorXd& diag, const Eigen::VectorXd& qtf,
                double radius, DoglegWorkspace& w, Eigen::VectorXd& step) {
  const Eigen::Index n = qtf.size();
  // Gauss–Newton step: R p = −qtf; a zero pivot is replaced by a tiny
  // multiple of its column so a singular R still yields a finite direction.
  Eigen::VectorXd& gauss_newton = w.gauss_newton;
  for (Eigen::Index j = n - 1; j >= 0; --j) {
    double sum = -qtf[j];
    for (Eigen::Index i = j + 1; i < n; ++i) sum -= r(j, i) * gauss_newton[i];
    double pivot = r(j, j);
    if (pivot == 0.0) {
      pivot = kEpsilon * r.col(j).head(j + 1).cwiseAbs().maxCoeff();
      if (pivot == 0.0) pivot = kEpsilon;
    }
    gauss_newton[j] = sum / pivot;
  }
  w.scaled_newton = diag.cwiseProduct(gauss_newton);
  const double gn_norm = w.scaled_newton.norm();
  if (gn_norm <= radius) {
    step = gauss_newton;
    return;
  }

  // Steepest descent of ½‖qtf + R p‖² in scaled variables: −D⁻¹ Rᵀ qtf.
  w.gradient.noalias() = r.transpose() * qtf;
  w.gradient.array() /= diag.array();
  const double gradient_norm = w.gradient.norm();
  if (gradient_norm == 0.0) {
    step = gauss_newton * (radius / gn_norm);
    return;
  }
  w.direction = -(w.gradient / gradient_norm);  // scaled, unit
  w.unscaled = w.direction.cwiseQuotient(diag);
  w.image.noalias() = r * w.unscaled;
  const double curvature = w.image.norm();
  const double cauchy_length =
      curvature > 0.0 ? gradient_norm / (curvature * curvature) : std::numeric_limits<double>::infinity();
  if (cauchy_length >= radius) {
    step = (radius * w.direction).cwiseQuotient(diag);
    return;
  }

  // Walk from the Cauchy point towards Gauss–Newton until ‖y‖ = radius:
  // ‖y_c + τ d‖² = radius², τ in (0, 1).
  w.cauchy = cauchy_length * w.direction;
  w.difference = w.scaled_newton - w.cauchy;
  const double a = w.difference.squaredNorm();
  const double b = w.cauchy.dot(w.difference);
  const double c = w.cauchy.squaredNorm() - radius * radius;  // < 0
  const double root = std::sqrt(b * b - a * c);
  const double tau = b > 0.0 ? -c / (b + root) : (root - b) / a;
  step = (w.cauchy + tau * w.difference).cwiseQuotient(diag);
}

Eigen::VectorXd doglegStep(const Eigen::MatrixXd& r, const Eigen::VectorXd& diag,
                           const Eigen::VectorXd& qtf, double radius) {
  DoglegWorkspace workspace(qtf.size());
  Eigen::VectorXd step(qtf.size());
  doglegStep(r, diag, qtf, radius, workspace, step);
  return step;
}

void rankOneUpdate(Eigen::MatrixXd& q, Eigen::MatrixXd& r, Eigen::VectorXd& qtf,
                   Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  const Eigen::Index n = r.rows();
  // 1. Rotate u onto e₁ from the bottom up; R becomes upper Hessenberg.
  // Rows i−1 and i of R are zero left of column i−1: rotate the rest only.
  for (Eigen::Index i = n - 1; i > 0; --i) {
    double c, s;
    u[i - 1] = givens(u[i - 1], u[i], &c, &s);
    u[i] = 0.0;
    rotateRows(&r(i - 1, i - 1), &r(i, i - 1), n - i + 1, n, c, s);
    rotateColumns(q.col(i - 1).data(), q.col(i).data(), q.rows(), c, s);
    double a = qtf[i - 1], b = qtf[i];
    qtf[i - 1] = c * a + s * b;
    qtf[i] = -s * a + c * b;
  }
  // 2. Add the rank-one term, now confined to the first row.
  r.row(0) += u[0] * v.transpose();
  // 3. Chase the subdiagonal away (rows i and i+1 start at column i).
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    double c, s;
    givens(r(i, i), r(i + 1, i), &c, &s);
    rotateRows(&r(i, i), &r(i + 1, i), n - i, n, c, s);
    r(i + 1, i) = 0.0;
    rotateColumns(q.col(i).data(), q.col(i + 1).data(), q.rows(), c, s);
    double a = qtf[i], b = qtf[i + 1];
    qtf[i] = c * a + s * b;
    qtf[i + 1] = -s * a + c * b;
  }
}

void PowellDogleg::run(MonitoredSystem& system, const Eigen::VectorXd& z0,
                       const SolverOptions& options, SolverResult& result) {
  Settings settings;
  std::string why;
  if (!parseSettings(options, &settings, &why)) {
    result.termination = Termination::kInvalidOptions;
    result.native_message = why;
    return;
  }
  // Large systems: Newton–dogleg on a sparse LU (Broyden updates would fill
  // the factors; both policies take the weak Jacobian at every iterate there).
  if (useSparseAlgebra(system, options))
    return runSparseNewtonDogleg(system, z0, options, settings, result);
  if (!denseBackendAccepts(name() + " (dense QR)", system.size(), kDenseMostUnknowns, options, result))
    return;
  const Eigen::Index n = system.size();
  // Every vector of the iteration is made here, once.
  Eigen::VectorXd z = z0, g(n), trial(n), g_trial(n), step(n), model_residual(n), qt_trial(n), u(n), v(n);
  DoglegWorkspace workspace(n);
  Eigen::MatrixXd jacobian(n, n), q(n, n), r(n, n);
  Eigen::VectorXd diag = Eigen::VectorXd::Ones(n), qtf(n);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(n, n);
  result.solution = z;

  auto finish = [&](Termination t, int code, const char* message) {
    result.termination = t;
    result.native_code = code;
    result.native_message = message;
    result.solution = z;
  };

  if (!system.residual(z, g)) return finish(Termination::kEvaluationFailed, -1, "residual failed at the initial guess");
  double g_norm = g.norm();
  if (g_norm <= options.residual_tolerance) return finish(Termination::kConverged, 0, "initial guess within tolerance");

  double radius = 0.0, z_norm = 0.0;
  int consecutive_successes = 0, consecutive_failures = 0;
  int slow_steps = 0, slow_jacobians = 0;
  bool no_success_yet = true;

  while (true) {
    // ---- fresh weak Jacobian and its QR factorisation
    if (!system.residualAndJacobian(z, g, jacobian))
      return finish(Termination::kEvaluationFailed, -1, "Jacobian evaluation failed");
    g_norm = g.norm();
    qr.compute(jacobian);
    q = qr.householderQ();
    r = qr.matrixQR().triangularView<Eigen::Upper>();
    // Until a step succeeds, every Jacobian restarts the scaling and the
    // radius from scratch (MINPACK's iter == 1 block): a first model that
    // overshot says nothing about the right radius for the next one.
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
    qtf.noalias() = q.transpose() * g;
    bool fresh_jacobian = true;

    // ---- trust-region steps on this (then Broyden-updated) model
    while (true) {
      if (result.iterations >= options.max_iterations)
        return finish(Termination::kIterationLimit, 6, "iteration limit");
      ++result.iterations;
      doglegStep(r, diag, qtf, radius, workspace, step);
      const double step_norm = diag.cwiseProduct(step).norm();
      // Until a first step succeeds, the radius never exceeds the step taken
      // (MINPACK's iter == 1 rule).
      if (no_success_yet) radius = std::min(radius, step_norm);

      trial = z + step;
      if (!system.residual(trial, g_trial))
        return finish(Termination::kEvaluationFailed, -1, "residual evaluation failed");
      const double trial_norm = g_trial.norm();
      const double actual = trial_norm < g_norm ? 1.0 - std::pow(trial_norm / g_norm, 2) : -1.0;
      model_residual.noalias() = r * step;  // Qᵀ(g + J p) = qtf + R p
      model_residual += qtf;
      const double model_norm = model_residual.norm();
      const double predicted = model_norm < g_norm ? 1.0 - std::pow(model_norm / g_norm, 2) : 0.0;
      const double ratio = predicted > 0.0 ? actual / predicted : 0.0;

      dogleg::updateTrustRadius(ratio, step_norm, radius, consecutive_successes);
      consecutive_failures = ratio < 0.1 ? consecutive_failures + 1 : 0;

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

      if (g_norm <= options.residual_tolerance)
        return finish(Termination::kConverged, 0, "residual within tolerance");
      if (radius <= settings.xtol * z_norm || g_norm == 0.0)
        return finish(Termination::kStepTolerance, 1, "trust radius below xtol relative to |D z|");
      if (system.evaluationLimitReached())
        return finish(Termination::kEvaluationLimit, 2, "evaluation limit");
      if (system.timeLimitReached()) return finish(Termination::kTimeLimit, 7, "time limit");
      if (0.1 * std::max(0.1 * radius, step_norm) <= kEpsilon * z_norm)
        return finish(Termination::kStepTolerance, 3, "steps below machine precision");
      if (slow_jacobians == 5)
        return finish(Termination::kNotProgressing, 4,
                      "no progress over the last five Jacobian evaluations");
      if (slow_steps == 10)
        return finish(Termination::kNotProgressing, 5, "no progress over the last ten iterations");

      if (policy_ == JacobianPolicy::kEveryIteration) {
        if (accepted) break;  // new iterate: new weak Jacobian
        fresh_jacobian = false;
        continue;  // same point, same exact model, smaller radius
      }
      if (consecutive_failures == 2) break;

      // Broyden update of Q R: J⁺ = J + (g⁺ − g − J p)(D²p)ᵀ / ‖Dp‖², in
      // the rotated frame Rᵀ-side u = (Qᵀg⁺ − Qᵀg − R p)/‖Dp‖.
      qt_trial.noalias() = q.transpose() * g_trial;
      u = (qt_trial - model_residual) / step_norm;
      v = diag.cwiseProduct(diag.cwiseProduct(step)) / step_norm;
      if (accepted) qtf = qt_trial;
      rankOneUpdate(q, r, qtf, u, v);
      fresh_jacobian = false;
    }
  }
}

}  // namespace eqhb
