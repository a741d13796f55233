// The sliders of a four-parameter Iwan element (Segalman, "A four-parameter
// Iwan model for lap-type joints", J. Appl. Mech. 72, 2005), for the
// alternating frequency–time law of jenkins_aft.h. The element is a
// continuum of Jenkins sliders in parallel; a slider of slip displacement φ
// (the spring's stretch when it slips) has stiffness ρ(φ) dφ, with
//   ρ(φ) = R φ^χ  on (0, φ_max),  plus S δ(φ − φ_max),
// fixed by the joint's slip force F_S (the force when every slider slips,
// ∫ φ ρ), its stiffness K_T (every slider stuck, ∫ ρ), χ > −1 (the
// exponent of the micro-slip dissipation, D ∝ a^{χ+3} for small amplitude
// a) and β >= 0 (the share of the concentrated part):
//   φ_max = F_S (1 + β) / (K_T (β + (χ+1)/(χ+2))),
//   R = F_S (χ+1) / (φ_max^{χ+2} (β + (χ+1)/(χ+2))),  S = F_S β / (φ_max (β + (χ+1)/(χ+2))).
// χ = 0, β = 0 is the uniform distribution of slip displacements on
// (0, 2 F_S / K_T).
//
// Discretised on `cells` equal cells of (0, φ_max): one slider per cell
// with the density's exact stiffness ∫ρ and slip force ∫φρ over the cell,
// plus one slider (S, S φ_max) when β > 0. K_T and F_S are thus exact for
// any number of cells, and the slip forces spread over the cells as the
// density does.
#pragma once

#include <vector>

#include "eqhb/laws/joints/jenkins_aft.h"

namespace eqhb {

struct IwanParameters {
  double slip_force = 1.0;  // F_S > 0
  double stiffness = 1.0;   // K_T > 0
  double chi = 0.0;         // χ > −1
  double beta = 0.0;        // β >= 0
  int cells = 20;           // >= 1
};

// φ_max of the parameters.
double iwanMaxSlipDisplacement(const IwanParameters& p);
// The sliders (mu_n: slip force, k_t: stiffness), `cells` (+1 when β > 0);
// throws InputError naming the field for a parameter out of its range.
std::vector<JenkinsAft::Slider> iwanSliders(const IwanParameters& p);

}  // namespace eqhb
