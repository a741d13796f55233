// The problem's own scales of force, displacement and velocity, in which
// convergence is measured, so that a problem and the same problem in other
// units get the same verdict:
//
//   F₀ = the largest load amplitude and law force level (μN, a preload),
//   X₀ = the largest amplitude of the linear response (the structure without
//        its laws under the loads) at the laws' DOFs, or a law length (a
//        gap) when larger,
//   s  = the dynamic stiffness at the laws' DOFs, max_i max(K_ii, ωC_ii, ω²M_ii),
//   F  = F₀ (s X₀ without loads),  X = X₀ (F₀ / s without a response),  V = ωX.
//
// The response, not F₀ / s, sets X: a structure forced near a resonance moves
// far more than its local stiffness says (a beam's tip). A problem without
// any force or length has the zero solution; its scales are then 1, the
// absolute measure.
#pragma once

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/laws/law.h"

#include <string>
#include <vector>

namespace eqhb {

// `response` = X₀ from the linear response (0 when not known or unforced).
PhysicalScales physicalScales(const HbModel& model, double response);

// The largest |x_lin| at the laws' DOFs over the basis harmonics (amplitude
// √(a² + b²)), x_lin = A_k⁻¹ f_k; one dense or sparse factorisation per harmonic.
double linearResponseAtLaws(const HbModel& model, bool sparse);

// The model with every scale-free ρ and width set (Law::withScaleFreeRho) from the
// driving-point compliance of the structure at each law's DOFs (the largest
// over them): the smaller of the static |(K⁻¹)_ii| and the dynamic
// |(A₁⁻¹)_ii| at the fundamental, by one factorisation of K and A₁ and one
// solve per law DOF (see drivingPointCompliances). Laws given a ρ are kept.
HbModel withScaleFreeRhos(HbModel model);
// The same from the static compliance |(K⁻¹)_ii| alone, for a system whose
// ω is a resonance of its own (a nonlinear mode): there the dynamic
// compliance is infinite at a free mode, or nil at a DOF the mode holds (its
// antiresonance), and says nothing of the scales. Laws keep their factor ρ
// where K is singular.
HbModel withStaticScaleFreeRhos(HbModel model);

// Why a solve may have failed because of a badly scaled constant: for every
// law whose ρ in use is more than kRhoMisscale away from its scale-free
// value (either way), or whose regularisation width is more than
// kWidthMisscale away from its own (law.h), one sentence naming the law,
// both values and what to change. Empty otherwise.
inline constexpr double kRhoMisscale = 1e3;
std::vector<std::string> scaleAdvice(const HbModel& model);

// The width sentence of scaleAdvice for law `l` alone; empty when its width
// is within kWidthMisscale of the scale-free one or it has none.
std::string widthScaleAdvice(const HbModel& model, int l);

}  // namespace eqhb
