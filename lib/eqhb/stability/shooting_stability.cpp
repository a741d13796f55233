#include "eqhb/stability/shooting_stability.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "eqhb/error.h"
#include "eqhb/orbits/default_restitution.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/stability/monodromy_stability.h"
#include "eqhb/stability/multiplier_stability.h"

namespace eqhb {

orbits::ShootingOptions ShootingStability::defaultShooting() {
  orbits::ShootingOptions o;
  o.tolerance = 1e-10;
  o.max_iterations = 20;
  o.time_limit = 2.0;
  return o;
}

bool ShootingStability::supports(const HbModel& model) {
  if (model.laws.empty()) return false;
  try {
    // The flow's constructor is the one authority on which laws it follows
    // (grounded, each with a closed-form or smooth-phase site).
    orbits::makeFlow(model, orbits::kHarmonicBalanceRestitution);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

ShootingStability::ShootingStability(const HbModel& model, const HillOptions& options,
                                     const orbits::ShootingOptions& shooting)
    : model_(model), options_(options), shooting_(shooting) {
  options_.validate();
  shooting_.validate();
  model_.validate();
  if (!supports(model_))
    throwInputError("stability_method", "\"shooting\"",
                    "needs laws with an exact flow (grounded coulomb-1d, jenkins on 1 DOF, signorini, "
                    "penalty-contact, cubic, polynomial, quadratic-damping, coulomb-2d, stribeck)");
  displacement_.resize(model_.samples, model_.structure.dofs());
}

ShootingStability::~ShootingStability() = default;

HillResult ShootingStability::fallback(double omega, const Eigen::VectorXd& full, const std::string& why) {
  HillResult r;
  if (MonodromyStability::supports(model_)) {
    if (!monodromy_) monodromy_ = std::make_unique<MonodromyStability>(model_, options_.unit_tolerance);
    r = monodromy_->analyse(omega, full);
  } else {
    if (!hill_) hill_ = std::make_unique<HillStability>(model_, options_);
    r = hill_->analyse(omega, full);
  }
  r.note = why + "; answered by " + (r.method == "monodromy" ? "the monodromy" : "Hill's method");
  return r;
}

HillResult ShootingStability::analyse(double omega, const Eigen::VectorXd& full) {
  const auto start = std::chrono::steady_clock::now();
  if (!(omega > 0.0) || !std::isfinite(omega)) throwInputError("omega", formatNumber(omega), "must be finite and > 0");
  const int n = model_.structure.dofs(), nb = model_.basis.size();
  model_.checkSolutionSize(full);
  model_.omega = omega;
  last_distance_ = std::nan("");
  last_ = orbits::ShootingResult();
  if (n > kMaxDofs)
    return fallback(omega, full,
                    "not shot: " + std::to_string(n) + " DOFs, above " + std::to_string(kMaxDofs) +
                        " (the exact flow's exponentials of the whole state cost minutes a point)");
  // The flow's phases (matrix exponentials with the forcing in the
  // generator) depend on ω, so each point gets its own flow; the model and
  // the work space are the curve's.
  const std::unique_ptr<orbits::Flow> flow = orbits::makeFlow(model_, orbits::kHarmonicBalanceRestitution);
  last_ = orbits::shootFromHarmonicBalance(*flow, model_, full, shooting_);
  if (!last_.converged) return fallback(omega, full, "shooting did not converge: " + last_.failure);
  // The series' displacement at the N samples, t_k = kT/N.
  const double period = 2.0 * M_PI / omega;
  const int samples = static_cast<int>(displacement_.rows());
  const std::vector<int>& harmonics = model_.basis.harmonics();
  for (int k = 0; k < samples; ++k) {
    const double t = period * k / samples;
    for (int i = 0; i < n; ++i) {
      double x = 0.0;
      for (size_t h = 0; h < harmonics.size(); ++h) {
        const int o = i * nb + model_.basis.offset(static_cast<int>(h));
        if (harmonics[h] == 0) {
          x += full[o];
          continue;
        }
        const double phase = harmonics[h] * omega * t;
        x += full[o] * std::cos(phase) + full[o + 1] * std::sin(phase);
      }
      displacement_(k, i) = x;
    }
  }
  last_distance_ = orbits::distanceToOrbit(*flow, last_, displacement_);
  if (!(last_distance_ <= kSameOrbitDistance)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "shooting converged to another orbit (displacement distance %.3g from the series, above %.2g)",
                  last_distance_, kSameOrbitDistance);
    return fallback(omega, full, text);
  }
  HillResult r = stabilityFromMultipliers(last_.multipliers, period, options_.unit_tolerance, "shooting");
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace eqhb
