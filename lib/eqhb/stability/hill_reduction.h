// The model Hill's method analyses on a large structure: reduced to its law
// DOFs and the fixed-interface modes the harmonics resolve (Craig–Bampton,
// interface_reduction.h), x = T q.
//
// Why: Hill's truncated basis resolves an exponent only where its frequency
// lies within the harmonics' band. A structure's modes far above it (a
// space frame's axial and torsion modes at 10⁶ rad/s against H ω = 3,000 on
// blade-tip-damper) come out of the pencil with spurious real parts: there
// they gave exponents of 1.4e4 ± 4.3e6 i, radii of 1e64 and "unstable",
// where the time-domain orbit started from the harmonic-balance one
// settles (periodic to 6e-10). A mode faster than the band (kResolvedBandMargin
// × k_max × ω) and damped follows the law DOFs statically in T instead, as
// in the monodromy's reduction; undamped ones are kept. The law DOFs stay
// coordinates of q, so each law reads the same u and its Jacobian is the
// same; only the structure's fast interior is gone.
#pragma once

#include <Eigen/Dense>
#include <optional>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

struct HillReduction {
  HbModel model;               // the structure Tᵀ(M, C, K)T and loads Tᵀf, the laws on q's law coordinates
  Eigen::MatrixXd projection;  // P: q = P x (P T = I)
  int modes_kept = 0, modes_dropped = 0;
  int full_dofs = 0;           // the unreduced structure's
  // A solution [x; λ] of the full model in the reduced model's layout;
  // throws InputError naming the solution if it is not of the full model.
  Eigen::VectorXd reduce(const Eigen::VectorXd& full) const;
};

// Empty when the structure has no more than `above` DOFs, has no laws, no
// mode is dropped, or its interior is not positive definite (a body held
// by its laws alone).
std::optional<HillReduction> reduceForHill(const HbModel& model, int above);

}  // namespace eqhb
