// Everything that defines one harmonic-balance problem: the linear structure,
// the laws attached to it, the Fourier basis, the sample count N and ω.
#pragma once

#include <string>
#include <vector>

#include "eqhb/harmonic_balance/harmonic_set.h"
#include "eqhb/laws/law.h"
#include "eqhb/structures/linear_structure.h"

namespace eqhb {

struct HbModel {
  LinearStructure structure;
  std::vector<AttachedLaw> laws;
  HarmonicSet basis{HarmonicKind::kOdd, 1};
  int samples = 64;
  double omega = 1.0;
  // What each DOF is, for the outputs (beams: "w3", "theta3"; frames also
  // "u3"); empty: "x1".."xn" (dofLabel, hb_solution.h).
  std::vector<std::string> dof_names;

  // Throws InputError naming the field: structure (see LinearStructure),
  // ω finite and > 0, N >= 2H+1, every law on existing, distinct DOFs with
  // one DOF per component, every load's harmonic inside the basis, harmonic 0
  // in the basis when a law needs the constant term (Law::needsConstantTerm).
  void validate() const;
  // Total number of law force components (unknown force channels).
  int lawComponents() const;
  // Global component index of component `a` of law `l` (order of `laws`).
  int componentIndex(int l, int a) const;
  // Throws InputError naming the solution unless `full` holds the [x; λ]
  // coefficients of a structure of `dofs` DOFs (default: this one's) with
  // these laws on this basis.
  void checkSolutionSize(const Eigen::VectorXd& full, int dofs = -1) const;
};

// N for `model` on `harmonics` harmonics when no N is given: a scene's N is
// chosen for its H, so a higher H keeps its samples per period of the
// highest harmonic (N raised in proportion to k_max: Duffing's 29 samples
// for 7 harmonics become 166 for 40, stribeck's 1024 for 10 odd harmonics
// 4258 for 40), a lower H keeps the scene's N; never below 2 k_max + 1.
// Why: the equality forms' kinks are sampled; at H = 40 on the scene's N
// (13 samples per period of k_max where the scene has 54) the arclength
// sweeps of stribeck and NLvib's unilateral wall stopped at spurious kinks
// (0.184, 0.742) and complete with N in proportion. Throws InputError for a
// harmonic count the basis refuses.
int samplesForHarmonics(const HbModel& model, int harmonics);

}  // namespace eqhb
