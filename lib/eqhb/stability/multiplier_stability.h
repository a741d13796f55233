// Floquet exponents and the stability verdict from the eigenvalues of a
// monodromy matrix (the multipliers), in the form Hill's method reports
// them: for the linearised monodromy over a harmonic-balance orbit
// (monodromy_stability.h) and for an exact orbit found by shooting
// (shooting.h), whose multipliers are its own.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "eqhb/stability/hill_stability.h"

namespace eqhb {

// Exponents s = log(μ) / T, largest |μ| first; stable when the spectral
// radius is below 1 + unit_tolerance. A multiplier 0 (a stuck DOF forgets
// its velocity) has no exponent: its logarithm is taken at the smallest
// positive double. `method` names where the multipliers came from.
HillResult stabilityFromMultipliers(const Eigen::VectorXcd& multipliers, double period, double unit_tolerance,
                                    const std::string& method);

}  // namespace eqhb
