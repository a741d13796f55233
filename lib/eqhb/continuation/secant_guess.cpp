#include "eqhb/continuation/secant_guess.h"

#include <cmath>
#include <limits>

namespace eqhb {

void SecantGuess::accept(double omega, const Eigen::VectorXd& z) {
  if (have_last_) {
    previous_ = last_;
    previous_omega_ = last_omega_;
    have_previous_ = true;
  }
  last_ = z;
  last_omega_ = omega;
  have_last_ = true;
}

double SecantGuess::scaledNorm(SquareSystem& system, const Eigen::VectorXd& z, int* evaluations) {
  ++*evaluations;
  if (!system.residual(z, residual_)) return std::numeric_limits<double>::infinity();
  const double norm = residual_.cwiseQuotient(scales_).norm();
  return std::isfinite(norm) ? norm : std::numeric_limits<double>::infinity();
}

Eigen::VectorXd SecantGuess::at(double omega, SquareSystem& system, const Eigen::VectorXd& fallback,
                                int* evaluations) {
  if (!have_previous_ || last_omega_ == previous_omega_ || fallback.size() != last_.size()) return fallback;
  const double t = (omega - last_omega_) / (last_omega_ - previous_omega_);
  const Eigen::VectorXd line = last_ + t * (last_ - previous_);
  residual_.resize(system.size());
  scales_.resize(system.size());
  system.residualScales(scales_);
  return scaledNorm(system, line, evaluations) < scaledNorm(system, fallback, evaluations) ? line : fallback;
}

}  // namespace eqhb
