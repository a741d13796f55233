// Exact Coulomb friction with a limit L that may vary from sample to sample
// (spec §2 "Coulomb 1D/2D" and §5), shared by the joint laws. With u the
// slip velocity (ẋ_t for a rigid contact, ẋ_t + ṙ/k_t for elastic
// friction), r the friction force on the structure and s = r − ρu:
//   minmax (1D):     Ψ = u + min(0, ρ(r+L) − u) + max(0, ρ(r−L) − u)
//   projection:      Ψ = r − proj_D(L)(s)
//   max:             Ψ = r max(L, ‖s‖) − L s
// With L = μN these are exactly the formulas of Coulomb1D / Coulomb2D (same
// branches, same ties), which is what the reduction tests check. With L = 0
// the minmax and projection forms give Ψ = ρr or r (r = 0, separation); the
// max form gives r ‖s‖, which also vanishes on s = 0: a singular root the
// projection form does not have.
#pragma once

#include <string>

#include "eqhb/laws/law.h"

namespace eqhb {

enum class FrictionForm { kMinMax, kProjection, kMax };

// Samples with a slip speed ‖u‖ above this fraction of max‖u‖ count as
// clearly sliding in the physical checks of an elastic slider (k_t). Its
// slip velocity u = ẋ + ṙ/k_t jumps from 0 to ẋ where stick ends, so the
// truncated series rings on both sides of that jump with an overshoot of
// 8.9% of the jump (Gibbs) at any H; the jump is at most max‖u‖, so above
// 10% no stuck sample is taken for sliding. (With 5%, as for the rigid laws
// whose slip velocity ẋ is continuous, the ringing in the short stick
// phases of jenkins-1d read as slip against the force: sliding_force_error
// 1.85 at H = 10 and 1.57 at H = 20, instead of falling with H.)
constexpr double kElasticSlidingFraction = 0.10;

// The size of Ψ for a unit relative error in the problem's scales (see
// Law::residualScale): minmax min(V, ρF), projection min(ρV, F), max F·min(F, ρV).
double frictionResidualScale(FrictionForm form, double rho, const PhysicalScales& scales);

// The scale-free ρ of a form for a slip mobility ω|G| (velocity per force):
// minmax compares u with ρr (ρ = mobility), projection and max compare r with
// ρu (ρ = 1 / mobility). See LawScales.
double scaleFreeFrictionRho(FrictionForm form, double mobility);

// The minmax form Ψ = u + min(0, a) + max(0, b), a = ρ(r + L) − u and
// b = ρ(r − L) − u (b <= a), by branch: ρ(r + L) where a < 0, ρ(r − L) where
// b > 0, u between; with lower/upper telling which branch is active. The
// same value as the sum, but the sum returns a sliding sample's ρ(r ± L) as
// u + (ρ(r ± L) − u), which rounds to 0 once ρF < 1e-16 V: the residual then
// reads 0 whatever the force (a false convergence at ρ = 1e-20).
struct MinMaxBranch {
  double psi;
  bool lower, upper;
};
inline MinMaxBranch minMaxBranch(double rho, double u, double r, double limit) {
  const bool lower = rho * (r + limit) - u < 0.0, upper = rho * (r - limit) - u > 0.0;
  const double psi = lower ? rho * (r + limit) : upper ? rho * (r - limit) : u;
  return {psi, lower, upper};
}

FrictionForm parseFrictionForm(const std::string& name, const std::string& field);
std::string frictionFormName(FrictionForm form);

// Ψ at one sample for m = 1 or 2 components, and its partials (m x m,
// row-major: d_u[a*m+b] = ∂Ψ_a/∂u_b; d_limit[a] = ∂Ψ_a/∂L). Throws nothing;
// the caller checks that minmax is used with m = 1.
struct FrictionPoint {
  double psi[2] = {0.0, 0.0};
  double d_u[4] = {0.0, 0.0, 0.0, 0.0};
  double d_r[4] = {0.0, 0.0, 0.0, 0.0};
  double d_limit[2] = {0.0, 0.0};
};
void evaluateFriction(FrictionForm form, int m, double rho, const double* u, const double* r,
                      double limit, FrictionPoint& out);

// argmin over the disc ‖λ‖ <= radius (an interval when m = 1) of
// ½ λᵀAλ + λᵀb, A symmetric definite (maximal dissipation on one time
// step): exact in 1D, projected gradient to round-off in 2D.
LocalVector minimiseOnDisc(const LocalMatrix& a, const LocalVector& b, double radius);

}  // namespace eqhb
