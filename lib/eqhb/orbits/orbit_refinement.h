// Harmonic balance followed by shooting: the harmonic-balance solution is the
// start of shooting (shooting.h), and the answer is the exact periodic orbit
// itself together with its Fourier truncation on the model's harmonics.
//
// Why: the equality-based formulation converges only as H^-1 or so on
// nonsmooth laws (the error sits in the first harmonic: the instants of
// stick, slip and contact are off), whereas the truncation of the exact orbit
// to the same harmonics is its best L2 approximation there, 100 to 10,000
// times closer. Shooting needs the HB solution only as a start inside Newton's
// basin, so a coarse H is enough; the refined coefficients then carry the
// best-approximation error of H and max|x| the exact one.
//
// Displacement coefficients: the orbit sampled at S equispaced instants of one
// period and projected by the trapezoidal rule, exact up to O(S^-3) on the C¹
// displacements of friction (O(S^-2) across impacts). Force coefficients: from
// the linear dynamics harmonic by harmonic, λ = forceSign · (A_k x − f_k) on
// the law's DOFs, exact given x (a direct quadrature of the discontinuous
// force would be O(S^-1)).
#pragma once

#include <Eigen/Dense>
#include <string>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/orbits/default_restitution.h"
#include "eqhb/orbits/shooting.h"

namespace eqhb::orbits {

struct RefinementOptions {
  ShootingOptions shooting;
  double restitution = kHarmonicBalanceRestitution;  // Newton's impact coefficient of contact laws, in [0, 1]
  // Harmonics of the truncation, same kind as the model's: 0 for the model's H.
  // Shooting's cost hardly depends on the start's H, so a coarse HB start can
  // be projected on many harmonics (its error then is the truncation's at that H).
  int output_harmonics = 0;
  // Instants per period for the projection; 0: max(256, 8 k_max) of the
  // output basis. Else >= 2 k_max + 1.
  int samples = 0;
  // Throws InputError naming the field.
  void validate(const HbModel& model) const;
  // The basis of the truncation for `model`.
  HarmonicSet outputBasis(const HbModel& model) const;
};

struct RefinedSolution {
  bool converged = false;    // shooting converged and the orbit was sampled
  std::string failure;       // why not
  ShootingResult orbit;
  HarmonicSet basis{HarmonicKind::kOdd, 1};  // of the truncation: the model's or output_harmonics
  Eigen::VectorXd full;      // [x; λ] coefficients of the exact orbit on `basis` (FullSystem layout)
  Eigen::VectorXd max_abs;   // exact max_t |x_i(t)| of the orbit
  int samples = 0;           // instants of the projection
  double seconds = 0.0;      // shooting and projection
};

// Shoots from `full` (a harmonic-balance solution of `model`, FullSystem
// layout) and projects the orbit on model.basis (or output_harmonics). Throws InputError for laws
// without an exact flow (see makeFlow) and bad options.
RefinedSolution refineByShooting(const HbModel& model, const Eigen::VectorXd& full, const RefinementOptions& options);

// The projection alone: Fourier coefficients on model.basis of the periodic
// orbit through `orbit.state` at `orbit.start_time` (false if the flow fails).
bool projectOrbit(const HbModel& model, const Flow& flow, const ShootingResult& orbit, int samples,
                  Eigen::VectorXd* full);

}  // namespace eqhb::orbits
