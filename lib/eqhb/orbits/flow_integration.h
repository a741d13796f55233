// Book-keeping both exact flows share while they integrate: the limits on
// events, the check of the start, the sample matrices and the saltation of
// the Jacobian at an event,
//   S = R + (f⁺ − R f⁻) ∇gᵀ / ġ
// (R the Jacobian of the reset, f∓ the vector fields before and after, ġ the
// rate of the event function; a grazing event, ġ = 0, leaves R alone: its
// time does not move to first order).
#pragma once

#include <Eigen/Dense>

#include "eqhb/orbits/piecewise_linear_flow.h"

namespace eqhb::orbits {

// Most events in one integration: beyond, impacts or stick-slip accumulate.
constexpr int kMaxEvents = 200000;
// Most events in a row at one instant before the phase is called inconsistent.
constexpr int kMaxImmediateEvents = 8;

// False, with result.failure set, unless y0 has `size` finite entries and
// t0 and duration >= 0 are finite.
bool validStart(const Eigen::VectorXd& y0, int size, double t0, double duration, FlowResult& result);

// Sizes the sample matrices (if any) for `dofs` DOFs and `forces` law components.
void prepareSamples(FlowSamples* samples, int dofs, int forces);

// jacobian ← S · jacobian.
void applySaltation(const Eigen::MatrixXd& reset, const Eigen::VectorXd& f_before, const Eigen::VectorXd& f_after,
                    const Eigen::RowVectorXd& gradient, double g_rate, Eigen::MatrixXd& jacobian);

}  // namespace eqhb::orbits
