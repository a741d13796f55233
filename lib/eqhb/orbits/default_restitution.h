#pragma once

namespace eqhb::orbits {

// The impact law an orbit shot from a harmonic-balance solution gets by
// default: elastic (e = 1). The Signorini equality form has no impact law;
// with the gap times the pressure nil at every instant, the contact force
// does no work over a period, and its harmonic balance approaches the
// elastic-impact orbit as H grows (problems/contact.toml at ω = 0.5, relative
// L2 distance of the coefficients: 0.20, 0.14, 0.091, 0.068, 0.039 at
// H = 5, 10, 20, 30, 60; to the plastic orbit 0.25 at H = 20). Shooting from
// it with another e finds another orbit.
inline constexpr double kHarmonicBalanceRestitution = 1.0;

}  // namespace eqhb::orbits
