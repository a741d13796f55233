#include "eqhb/backends/dogleg/powell_dogleg.h"

#include "eqhb/backends/dogleg/dense_dogleg_strategy.h"
#include "eqhb/backends/dogleg/dense_lu_strategy.h"
#include "eqhb/backends/dogleg/sparse_newton_dogleg.h"
#include "eqhb/backends/dogleg/trust_region_loop.h"

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
    } else if (key == "factorisation") {
      if (text == "auto") settings->factorisation = Settings::Factorisation::kAuto;
      else if (text == "qr") settings->factorisation = Settings::Factorisation::kQr;
      else if (text == "lu") settings->factorisation = Settings::Factorisation::kLu;
      else {
        *why = "factorisation = \"" + text + "\": must be \"auto\", \"qr\" or \"lu\"";
        return false;
      }
    } else if (key == "update") {
      if (text == "refresh") settings->update = Settings::Update::kRefresh;
      else if (text == "broyden") settings->update = Settings::Update::kBroyden;
      else {
        *why = "update = \"" + text + "\": must be \"refresh\" or \"broyden\"";
        return false;
      }
    } else {
      *why = "unknown dogleg option \"" + key + "\" (known: factor, xtol, scaling, factorisation, update)";
      return false;
    }
  }
  return true;
}

}  // namespace

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
  const bool lu = settings.factorisation == DoglegSettings::Factorisation::kLu ||
                  (settings.factorisation == DoglegSettings::Factorisation::kAuto &&
                   system.size() >= kDenseLuFromUnknowns);
  if (lu) {
    dogleg::DenseLuStrategy strategy(system, policy_, settings.update == DoglegSettings::Update::kRefresh);
    return dogleg::runTrustRegionLoop(system, z0, options, settings, strategy, result);
  }
  dogleg::DenseDoglegStrategy strategy(system, policy_);
  dogleg::runTrustRegionLoop(system, z0, options, settings, strategy, result);
}

}  // namespace eqhb
