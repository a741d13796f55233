// Stability of a harmonic-balance solution by Hill's method on the full
// system's weak Jacobian.
//
// A perturbation y(t) = e^{st} p(t) of the periodic solution (p T-periodic,
// on the solution's Fourier basis) satisfies the linearised dynamics and
// laws. In the dynamics d/dt acts on e^{st} p as (s + D), D the derivative
// of the basis, so each harmonic's i k ω becomes s + i k ω:
//     M (s + D)² p + C (s + D) p + K p − W q = 0,
// and the laws, linearised pointwise with the weak partials of Ψ, give
//     P(Ψ_x p + Ψ_v (s + D) p + Ψ_λ q + Ψ_λ̇ (s + D) q) = 0
// (P the Galerkin projection). Where a law sticks or closes its rows are
// constraints on p, where it slips they leave q free. At s = 0 this is
// exactly the weak Jacobian J of the full system, so the quadratic
// eigenproblem is
//     J v + s B₁ v + s² B₂ v = 0,   B₂ = M on the displacement rows only.
// With w = s p it becomes the linear pencil A u = s B u on u = [p; q; w],
// A = diag(J, I). Its finite eigenvalues s are the Floquet exponents, each
// repeated as s + i m Ω (Ω = ω, or 2ω on a basis of odd harmonics whose
// perturbations are T/2-antiperiodic), the copies differing only in which
// harmonic carries the eigenvector.
//
// Selection criterion (stated): for each eigenvector the centroid κ of its
// displacement part over the complex harmonics, κ = Σ k |c_k|² / Σ |c_k|²
// (c_{±k} = (a_k ∓ i b_k)/2 from the cos/sin coefficients a_k, b_k). The
// meaningful copy of an exponent has its eigenvector centred on the reference
// harmonic r (0 for all harmonics, +1 for odd ones), so exponents are taken
// in increasing |κ − r|, one per family (a copy s + i m Ω, m ≠ 0, of one
// already taken is skipped), at most 2n (the state dimension). Multipliers
// are exp(s T); the solution is stable iff all lie inside the unit circle.
//
// Small systems: the pencil reduced to a standard eigenproblem
// (A − σB)⁻¹B on the columns where B is nonzero, solved dense: eigenvalues
// by Eigen's real Schur form, eigenvectors of the finite ones only by
// inverse iteration (dense_eigenproblem.h). Large ones: the same operator applied through a sparse LU
// and its largest eigenvalues (the exponents nearest the shift σ) from
// Spectra's Arnoldi solver (shift-invert).
#pragma once

#include <atomic>

#include <Eigen/Dense>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

struct HillOptions {
  // Pencils up to this many unknowns are solved dense, larger ones sparse.
  int dense_limit = 1500;
  // Sparse: eigenvalues requested from the Arnoldi solver, the exponents
  // nearest the shift σ = 0 (0: 40, capped by the size); only these are
  // candidates, so a large structure reports its least damped exponents.
  int sparse_eigenvalues = 0;
  // Structures of more DOFs are analysed reduced to their law DOFs and the
  // fixed-interface modes within the harmonics' band (hill_reduction.h);
  // 0: never reduced.
  int reduce_above = 20;
  // A multiplier counts as on the unit circle within this margin; stable
  // means spectral radius < 1 + unit_tolerance.
  double unit_tolerance = 1e-6;
  // "hill" (this file), "monodromy" (monodromy_stability.h: only on the
  // laws it supports), "shooting" (shooting_stability.h: the exact orbit's
  // multipliers, only on laws with an exact flow) or "auto" (the monodromy
  // where it applies, else Hill; curve_stability.h). The command line and
  // Python default to "auto".
  std::string method = "hill";
  // Seconds for the stability of a whole curve (analyseCurveStability), 0:
  // none. Checked after each point: the points not reached keep no verdict.
  double time_limit = 0.0;
  // Set from outside (a signal handler): the curve's stability stops there
  // too, as at its time limit.
  const std::atomic<bool>* stop_requested = nullptr;
  // Throws InputError naming the field.
  void validate() const;
};

struct FloquetExponent {
  std::complex<double> exponent;    // s
  std::complex<double> multiplier;  // exp(s T)
  double centroid = 0.0;            // κ of its eigenvector
};

struct HillResult {
  std::vector<FloquetExponent> exponents;  // selected, largest |multiplier| first
  double spectral_radius = 0.0;
  bool stable = false;
  int state_dimension = 0;   // 2n: the number of exponents sought (2m on a reduced structure)
  int candidates = 0;        // finite eigenvalues examined
  int pencil_size = 0;       // unknowns of the pencil
  bool sparse = false;       // Spectra (true) or the dense solver
  std::string method = "hill";  // or "monodromy" / "shooting": exponents from their multipliers
  double seconds = 0.0;
  std::string failure;       // nonempty when no exponent could be computed
  // Why `method` answered instead of the one asked (shooting that failed or
  // reached another orbit); empty otherwise.
  std::string note;
};

// Hill's method about the solution `full` = [x; λ] coefficients of `model`
// (at model.omega). Throws InputError if the model is invalid or `full`
// has the wrong size.
HillResult hillStability(const HbModel& model, const Eigen::VectorXd& full,
                         const HillOptions& options = {});

// The same for many solutions of one model at different ω (the points of a
// curve): what does not depend on the point (the full system and its
// Jacobian pattern, Fourier transforms, work space) is made once. Results
// are hillStability's of the model with that ω.
class HillStability {
 public:
  // Throws InputError if the model or the options are invalid.
  explicit HillStability(const HbModel& model, const HillOptions& options = {});
  ~HillStability();
  HillStability(const HillStability&) = delete;
  HillStability& operator=(const HillStability&) = delete;
  // Throws InputError if ω is not finite and > 0 or `full` has the wrong size.
  HillResult analyse(double omega, const Eigen::VectorXd& full);

  struct Work;  // defined in the source

 private:
  HillOptions options_;
  std::unique_ptr<Work> work_;
};

// Multipliers with |ρ| >= 1 + unit_tolerance.
int unstableMultipliers(const HillResult& result, double unit_tolerance = HillOptions().unit_tolerance);

// The bifurcation between two points of a curve, read from the change in the
// number of multipliers outside the unit circle: "fold" (a real one through
// +1: turning point, or a branch point of the symmetric solution),
// "period-doubling" (a real one through −1), "neimark-sacker" (a complex
// pair), or "" when that number is the same. A point may be unstable on
// both sides (another multiplier outside) and still be a fold.
std::string bifurcationKind(const HillResult& before, const HillResult& after,
                            double unit_tolerance = HillOptions().unit_tolerance);

}  // namespace eqhb
