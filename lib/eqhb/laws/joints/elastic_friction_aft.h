// Elastic dry friction under a varying normal load in the alternating
// frequency–time form (formulation = "aft"): the joint element tmdsimpy and
// pyHarm build interfaces from. It reads u = W x on [n, t1] (2D) or
// [n, t1, t2] (3D) (law_attachment.h) and
//   normal      p(t) = k_n max(0, u_n(t) − g0)     (penalty-contact's law),
//   tangential  T(t) = k_t (u_t(t) − w(t)),   ‖T‖ <= μ p(t),
// a spring k_t in series with a Coulomb slider at w whose limit follows the
// normal load. λ = (p, T) is the force on the contact, so the force on the
// structure is −λ (forceSign −1, penalty-contact's convention: the wall at
// u_n = g0 approached from below, gap g0 − u_n). Per sample, from the state w
// (the return map; a radial return on the disc of radius μp in 3D):
//   trial  T* = k_t (u_t − w);
//   stick  ‖T*‖ <= μp: T = T*;
//   slip   ‖T*‖ >  μp: T = μp T*/‖T*‖ and w = u_t − T/k_t
// (open, p = 0: T = 0 and the slider follows the displacement, w = u_t), and
//   Ψ(t_i) = λ(t_i) − (p, T)[u](t_i).
//
// Periodic state: the map runs over the period from w = ū_t (the period's
// mean), pass after pass, until a pass ends where it started. With one
// tangent the map of a period is a composition of clamps w ↦ clamp(w,
// u_t − μp/k_t, u_t + μp/k_t), itself a clamp and so idempotent: the second
// pass is periodic, as for jenkins (jenkins_aft.h). With two tangents a
// slip's direction depends on the state before it, so the start fades only
// geometrically; at most kMaxPasses passes are run (the last is the force).
// A slider that never slips keeps w = ū_t: its force is mean-free, so a
// period that sticks throughout adds k_t at every harmonic but the constant
// one (a periodic orbit does not fix a stuck slider; the mean adds no static
// force of its own). Anchored (anchoredAt, after a static preload): the
// first pass starts at the static slider position instead, which a slider
// that never slips keeps.
//
// Jacobian (exact almost everywhere): ∂Ψ_n/∂u_n = −k_n where pressed; for a
// tangent a, ∂Ψ_a(t_i)/∂u_b(t_j) = −k_t δ_ab δ_ij + k_t ∂w_a(t_i)/∂u_b(t_j),
// the slider's sensitivity carried through the passes (stick: kept; slip:
// ∂w = (I − P) ∂u_t − (μ/k_t) e ∂p + P ∂w_prev with e = T*/‖T*‖ and
// P = (μp/‖T*‖)(I − e eᵀ), 0 with one tangent), which reaches every sample:
// the law has one history term per sample (historyTermsOn): d² N² weights,
// 37k on 64 samples in 3D (295 KB per element), quadratic in N.
//
// Time reference (solveStep): the element is contact-friction with a
// compliant normal of stiffness k_n, no preload and k_t, whose λ is the
// negative of this one's (its λ is the force on the structure, this one's
// the force on the contact). The step is that law's: the penalty pressure at
// the step's end and the slider's return map, a minimum over the disc of
// radius μp in the metric of the spring and the structure's response (the
// radial return when the structure is rigid). The slider's state rides on
// the previous step's force: w = u_t − T/k_t at the step's start, and an
// open contact (T = 0) leaves the slider at u_t, released.
//
// Jenkins on a plane (constant_limit set: the `jenkins` law on 2 DOFs in the
// AFT form): no normal component; the slider's limit is μN throughout, the
// law's components are the tangents alone, and λ is the force on the
// structure as the other jenkins forms have it, λ = −T (forceSign +1), so
// Ψ_a = λ_a + T_a and the Jacobian's signs turn with it. Its time reference
// is the equality-form Jenkins' step on the same plane.
#pragma once

#include <optional>
#include <vector>

#include "eqhb/laws/joints/contact_friction.h"
#include "eqhb/laws/law.h"

namespace eqhb {

struct ElasticFrictionParameters {
  int tangents = 1;      // 1 (2D: [n, t1]) or 2 (3D: [n, t1, t2])
  double mu = 0.0;       // friction coefficient, >= 0
  double k_t = 0.0;      // tangential stiffness, > 0
  double k_n = 0.0;      // normal penalty stiffness, > 0
  double gap = 0.0;      // g0, the wall's position along n, finite
  // Set: no normal component, a constant limit μN (>= 0, finite): Jenkins on
  // a plane (the header); k_n and gap unused.
  std::optional<double> constant_limit;
};

class ElasticFrictionAft : public Law {
 public:
  // The passes run at most (see the header).
  static constexpr int kMaxPasses = 8;
  // Throws InputError naming the field: mu >= 0, k_t > 0, k_n > 0, gap, all
  // finite; tangents 1 or 2.
  explicit ElasticFrictionAft(const ElasticFrictionParameters& parameters);
  std::string type() const override { return onPlane() ? "jenkins" : "elastic-friction"; }
  int dimension() const override { return firstTangent() + p_.tangents; }
  double forceSign() const override { return onPlane() ? 1.0 : -1.0; }
  bool usesDisplacement() const override { return true; }
  bool usesVelocity() const override { return false; }
  bool needsConstantTerm() const override { return !onPlane(); }
  double forceLevel() const override { return onPlane() ? *p_.constant_limit : 0.0; }
  double displacementLevel() const override;
  // One term per sample: on one sample (the static step, linear modes) 1.
  int historyTerms() const override { return 1; }
  int historyTermsOn(int samples) const override { return samples; }
  bool rateIndependent() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  // Relative to max(max p, the problem's force scale's floor): aft_force_error
  // max |λ − (p, T)[u]|, negative_pressure max(−λ_n, 0), force_limit_excess
  // max(‖λ_t‖ − μ max(λ_n, 0), 0).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // One step of the time reference (the header): contact-friction's step
  // with the signs of λ and of the Delassus operator turned.
  LocalVector solveStep(const StepProblem& step) const override;
  std::optional<StaticStatus> staticStatus(const LawSamples& rest) const override;
  // A copy whose slider starts at its state after the static step from
  // w = 0 to the displacement of `rest` (the return map of one sample).
  std::shared_ptr<Law> anchoredAt(const LawSamples& rest) const override;
  const ElasticFrictionParameters& parameters() const { return p_; }
  // Jenkins on a plane: no normal component (the header).
  bool onPlane() const { return p_.constant_limit.has_value(); }
  // The law component of the first tangent: 0 on a plane, else 1.
  int firstTangent() const { return onPlane() ? 0 : 1; }
  const std::vector<double>& anchor() const { return anchor_; }

 private:
  ElasticFrictionParameters p_;
  std::optional<ContactFriction> step_law_;  // the same element as contact-friction, for solveStep (none on a plane)
  std::vector<double> anchor_;  // the slider's static position; empty: start at ū_t
};

}  // namespace eqhb
