// The energy a friction force dissipates over a period against the energy
// its law demands: an average, so it tells a wrong force from the Gibbs
// ringing of a truncated series, which a worst-sample measure cannot.
#pragma once

#include <algorithm>

namespace eqhb {

// Summed over the samples of one period, with u the slip velocity, r the
// friction force and L its limit (μN, or μ max(p, 0)):
//   dissipation_deficit = 1 − (Σ −r·u) / (Σ L‖u‖).
// 0 where r = −L u/‖u‖ wherever it slips, 1 for no force at all, 2 for a
// force that drives the slip instead of resisting it. Left at 0 when the
// demanded energy is below `floor` (a contact that hardly slips: no verdict).
class DissipationDeficit {
 public:
  // r_dot_u = r·u at one sample, demanded = L‖u‖ there.
  void add(double r_dot_u, double demanded) {
    dissipated_ -= r_dot_u;
    demanded_ += demanded;
  }
  double value(double floor) const {
    return demanded_ > floor ? std::max(0.0, 1.0 - dissipated_ / demanded_) : 0.0;
  }

 private:
  double dissipated_ = 0.0;
  double demanded_ = 0.0;
};

// A converged residual whose dissipation_deficit reaches this is no solution
// (half the friction energy missing or more); on the shipped scenes' sweeps
// a correct solution stays far below (invariants.h, grossViolation).
inline constexpr double kGrossDissipationDeficit = 0.5;

}  // namespace eqhb
