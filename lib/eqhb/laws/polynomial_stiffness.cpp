#include "eqhb/laws/polynomial_stiffness.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

namespace {
// x^p by repeated multiplication (p >= 0): exact under x -> −x, which keeps
// the odd law odd bit for bit (Law::oddSymmetric).
double integerPower(double x, int p) {
  double out = 1.0;
  for (int k = 0; k < p; ++k) out *= x;
  return out;
}
}  // namespace

PolynomialStiffness::PolynomialStiffness(std::vector<double> coefficients, std::vector<int> exponents)
    : coefficients_(std::move(coefficients)), exponents_(std::move(exponents)) {
  if (coefficients_.empty() || coefficients_.size() != exponents_.size())
    throwInputError("coefficients", std::to_string(coefficients_.size()) + " values",
                    "must be as many as the exponents (" + std::to_string(exponents_.size()) + "), at least one");
  for (size_t k = 0; k < coefficients_.size(); ++k) {
    if (!std::isfinite(coefficients_[k]))
      throwInputError("coefficients[" + std::to_string(k) + "]", formatNumber(coefficients_[k]), "must be finite");
    if (exponents_[k] < 1 || exponents_[k] > kMaxExponent)
      throwInputError("exponents[" + std::to_string(k) + "]", std::to_string(exponents_[k]),
                      "must be an integer in [1, " + std::to_string(kMaxExponent) + "]");
    if (exponents_[k] % 2 == 0 && coefficients_[k] != 0.0) odd_ = false;
  }
}

double PolynomialStiffness::force(double x) const {
  double sum = 0.0;
  for (size_t k = 0; k < coefficients_.size(); ++k) sum += coefficients_[k] * integerPower(x, exponents_[k]);
  return sum;
}

double PolynomialStiffness::slope(double x) const {
  double sum = 0.0;
  for (size_t k = 0; k < coefficients_.size(); ++k)
    sum += coefficients_[k] * exponents_[k] * integerPower(x, exponents_[k] - 1);
  return sum;
}

void PolynomialStiffness::evaluate(LawSamples& s, bool with_derivatives) const {
  const Eigen::Index n = s.psi.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = s.displacement(i, 0);
    if (!with_derivatives) {
      s.psi(i, 0) = s.force(i, 0) + force(x);
      continue;
    }
    // P and P' from the same powers: x^p = x^(p−1) · x, as integerPower forms it.
    double value = 0.0, derivative = 0.0;
    for (size_t k = 0; k < coefficients_.size(); ++k) {
      const double below = integerPower(x, exponents_[k] - 1);
      value += coefficients_[k] * (below * x);
      derivative += coefficients_[k] * exponents_[k] * below;
    }
    s.psi(i, 0) = s.force(i, 0) + value;
    s.dpsi_ddisplacement(i, 0) = derivative;
    s.dpsi_dforce(i, 0) = 1.0;
  }
}

LocalVector PolynomialStiffness::solveStep(const StepProblem& step) const {
  // x_θ = x_start + θ h (θ u_end + (1 − θ) v_start), u_end = u_free + D λ.
  const double th = step.theta * step.h;
  const double base = step.x_start[0] + th * (step.theta * step.u_free[0] + (1.0 - step.theta) * step.v_start[0]);
  const double dx = th * step.theta * step.delassus(0, 0);
  auto phi = [&](double lambda) { return lambda + force(base + dx * lambda); };
  double lambda = -force(base), value = phi(lambda);
  for (int iteration = 0; iteration < 100 && value != 0.0; ++iteration) {
    const double derivative = 1.0 + slope(base + dx * lambda) * dx;
    double step_length = derivative != 0.0 ? -value / derivative : -value;
    // Halved until |φ| decreases: a softening polynomial can throw Newton far.
    double next = lambda + step_length, next_value = phi(next);
    for (int halving = 0; halving < 30 && !(std::abs(next_value) < std::abs(value)); ++halving) {
      step_length *= 0.5;
      next = lambda + step_length;
      next_value = phi(next);
    }
    const bool done = std::abs(next - lambda) <= 1e-15 * (1.0 + std::abs(lambda));
    lambda = next;
    value = next_value;
    if (done) break;
  }
  LocalVector out(1);
  out[0] = lambda;
  return out;
}

std::vector<std::pair<std::string, double>> PolynomialStiffness::violations(const LawSamples& s,
                                                                            const PhysicalScales& scales) const {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < s.force.rows(); ++i)
    worst = std::max(worst, std::abs(s.force(i, 0) + force(s.displacement(i, 0))));
  const double scale = std::max(invariantScale(s.force.col(0).cwiseAbs().maxCoeff(), scales.force), 1e-300);
  return {{"dae_residual", worst / scale}};
}

}  // namespace eqhb
