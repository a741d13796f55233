// A law Ψ(x, ẋ, λ) = 0 kept as an equality (spec §1–2), evaluated on a batch
// of N time samples at once: one virtual call per evaluation, not per sample.
//
// A law of dimension d reads d components u = W x of the structure's DOFs
// (law_attachment.h) and owns d force components λ; the force it applies on
// the structure is Wᵀ (forceSign() · λ). Its pointwise
// weak derivatives ∂Ψ_a/∂q_b (q = x, ẋ or λ) are returned as sample columns;
// the assembly turns them into Jacobian blocks.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/laws/law_attachment.h"

namespace eqhb {

// Column layout: component a of a quantity is column a; partial ∂Ψ_a/∂q_b is
// column a * d + b. Rows are the N time samples.
//
// A history law (Law::historyTermsOn(N) = K > 0, the alternating frequency–time
// forms) has Ψ at sample i depend on the displacement at other samples too:
//   ∂Ψ_a(t_i)/∂x_b(t_j) = dpsi_ddisplacement(i, ab) δ_ij
//                         + Σ_k history_weight(i, ab K + k) [j = history_sample(i, ab K + k)],
// where a sample index kPeriodMean stands for the mean over the period (the
// weight spread as 1/N on every sample). A term of weight 0 is unused.
struct LawSamples {
  static constexpr int kPeriodMean = -1;
  Eigen::MatrixXd displacement, velocity, force;  // N x d inputs
  Eigen::MatrixXd force_rate;                     // N x d input, λ̇ (laws with usesForceRate)
  Eigen::MatrixXd psi;                            // N x d output
  Eigen::MatrixXd dpsi_ddisplacement, dpsi_dvelocity, dpsi_dforce;  // N x d² outputs
  Eigen::MatrixXd dpsi_dforce_rate;                                 // N x d² output
  Eigen::MatrixXi history_sample;                                   // N x d² K output (history laws)
  Eigen::MatrixXd history_weight;                                   // N x d² K output (history laws)

  void resize(int samples, int dimension, int history_terms = 0);
};

// One time step of the nonsmooth reference integrator, seen by one law
// (Moreau–Jean / θ-method, see time_integrator.h): with the law's force λ
// held over the step, the velocity of its DOFs at the end of the step is
//   u_end = u_free + delassus · λ,
// and the displacement x_end = x_start + h (θ u_end + (1 − θ) v_start).
// Sizes are at most 3 (no heap allocation per step).
using LocalVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
using LocalMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
struct StepProblem {
  LocalVector x_start, v_start, u_free;
  LocalVector force_start;  // the law's force over the previous step (internal states)
  LocalMatrix delassus;  // h Wᵀ Ŵ⁻¹ W · forceSign, symmetric definite
  double h = 0.0, theta = 1.0;
  double restitution = 0.0;  // Newton impact coefficient (contact laws)
};

// The problem's own scales (harmonic_balance/problem_scales.h): a force, a
// displacement and a velocity, each > 0 (all 1: the absolute measure).
struct PhysicalScales {
  double force = 1.0, displacement = 1.0, velocity = 1.0;
};

// The structure as a law sees it, from which a scale-free ρ is made: the
// largest driving-point dynamic compliance |G_ii(ω)| = |(A₁⁻¹)_ii| at the
// law's DOFs (length per force, A₁ = K − ω²M + iωC at the fundamental) and ω.
// The condensed law equations weigh ω G λ (a velocity) or G λ (a gap) against
// ρ λ in their two branches, so ρ = ω|G| (or 1/|G|, 1/(ω|G|) by the form's
// units) gives both branches the same weight in any units (beam-joint-large's
// hand-set ρ = ω x³/(3EI) is this compliance, statically).
struct LawScales {
  double omega = 1.0;       // rad per unit time, > 0
  double compliance = 1.0;  // |G_ii(ω)|, > 0 and finite
  double mobility() const { return omega * compliance; }
};
// The balance above, times this weight on ρ: the contact stiffens the
// structure, so the free structure's compliance overstates what the law
// sees; 3 was the best weight of 1, 3 and 10 over the shipped scenes and
// NLvib's cantilever (every solve converged on its defaults at 3, one fewer
// at 10 and two fewer at 1; the damper's sweep lost 21 of 61 points at 3,
// 24 at 1, 27 at 10).
inline constexpr double kScaleFreeRhoWeight = 3.0;

// A law's ρ as the scene gives it: a value in the problem's units, or, with
// no value, `factor` times the scale-free ρ that a system sets from the
// structure at each ω (Law::withScaleFreeRho).
struct RhoSetting {
  RhoSetting(double rho = 1.0) : value(rho) {}  // a number is a given ρ
  static RhoSetting scaleFree(double factor = 1.0) {
    RhoSetting setting(factor);
    setting.scale_free = true;
    setting.factor = factor;
    return setting;
  }
  double value;  // the ρ in use (the factor until a system sets it scale-free)
  bool scale_free = false;
  double factor = 1.0;
  // The name of the scene key that set it, for messages.
  const char* field() const { return scale_free ? "rho_factor" : "rho"; }
};

// A regularised friction form (tanh, a ramp, a rounded norm) replaces the
// jump of the force at zero slip by a transition of some width. That width
// is a velocity and means nothing in itself: 0.01 is sharp for a mass that
// slides at 1 and a viscous damper for a steel beam sliding at 1e-6 m/s.
// Unless the scene gives it, it is set from the contact's own velocity scale
//   V_c = L ω|G|,
// the slip velocity that the force limit L drives through the structure's
// mobility at the contact (LawScales; the slip amplitudes of friction-1d
// and NLvib's cantilever are 2 and 3 times it), as kScaleFreeWidthFraction
// of V_c: sharp against any slip of that size, and the old fixed default
// (β = 100) wherever V_c is 1, as on friction-1d, whose answers it keeps.
// Measured on the cantilever in SI (N = 128): both tanh and piecewise sweep
// 101 of 101 points (β = 100 s/m: law_violated, a viscous damper).
inline constexpr double kScaleFreeWidthFraction = 1e-2;
// V_c for force limit L, or 1 (the absolute measure) where it is not > 0
// and finite (L = 0: a law that applies no force, whose width is immaterial).
inline double contactVelocityScale(const LawScales& scales, double force_limit) {
  const double v = force_limit * scales.mobility();
  return v > 0.0 && std::isfinite(v) ? v : 1.0;
}
// The scale-free width (a velocity) of a regularised form with force limit L.
inline double scaleFreeVelocityWidth(const LawScales& scales, double force_limit) {
  return kScaleFreeWidthFraction * contactVelocityScale(scales, force_limit);
}
// A width in use next to its scale-free value, both in the key's own terms
// (a slope β, 1/velocity, or a width): what a failure blames on a badly
// scaled width.
struct WidthComparison {
  const char* key;
  double in_use, scale_free;
};
// Widths more than this factor from their scale-free value (either way) are
// named when a solve fails (a slope 10 times too shallow already makes a
// friction force a viscous damper over the slip it should limit).
inline constexpr double kWidthMisscale = 10.0;

// The least scale an invariant is measured against, as a fraction of the
// problem's scale (the floor of compareWithReference's channels, 1e-3 of
// the largest, for the same reason).
inline constexpr double kInvariantScaleFloor = 1e-3;
// max(observed, kInvariantScaleFloor · problem): the scale of one measure.
inline double invariantScale(double observed, double problem) {
  return std::max(observed, kInvariantScaleFloor * problem);
}

// A law's state at rest under static loads (preload/static_contact.h): a
// contact open or closed (its gap g, positive open, and normal force p >= 0
// pressing), a friction stuck or slipping (its tangential force and limit).
// Fields a law does not have stay unset.
struct StaticStatus {
  enum class State { kOpen, kClosed, kStuck, kSlipping };
  State state = State::kClosed;
  std::optional<double> gap, normal_force;
  std::optional<double> tangential_force, friction_limit;  // ‖r_t‖ and μN (or μp)
};
const char* staticStateName(StaticStatus::State state);
// A friction force of size `force` against its limit: slipping at the limit
// (to a relative 1e-8, the solve's round-off) or where there is none.
StaticStatus frictionStatus(double force, double limit);

class Law {
 public:
  virtual ~Law() = default;
  virtual std::string type() const = 0;
  virtual int dimension() const = 0;
  // Sign of the force on the structure: +1 when λ is the force itself
  // (friction), −1 when λ is a pressure pushing in −x (contact).
  virtual double forceSign() const { return 1.0; }
  // Which inputs Ψ depends on; the assembly skips the others entirely.
  virtual bool usesDisplacement() const = 0;
  virtual bool usesVelocity() const = 0;
  // True when the law's force cannot be periodic without a mean: a one-sided
  // force (a contact pressure p >= 0) that is not zero has a positive mean,
  // so a basis without harmonic 0 could only meet the law by letting the
  // force change sign. Such a law needs the constant term in the basis.
  virtual bool needsConstantTerm() const { return false; }
  // The law's own force and length parameters (μN, a preload, a gap; 0 when
  // none), which enter the problem's scales.
  virtual double forceLevel() const { return 0.0; }
  virtual double displacementLevel() const { return 0.0; }
  // The size of Ψ_component that stands for a unit relative error in the
  // problem's scales. Ψ mixes force and velocity (or gap) through ρ, so a
  // residual is small only when it is small against the smaller of the two,
  // e.g. min(V, ρF) for a Coulomb min/max form (Ψ in velocity units). The
  // default, F, is for a Ψ in force units.
  virtual double residualScale(const PhysicalScales& scales, int component) const;
  // Ψ depends on λ̇ too (elastic friction: the slider moves at ẋ + λ̇/k_t).
  virtual bool usesForceRate() const { return false; }
  // True when Ψ is odd in its inputs, sample by sample and exactly in floating
  // point: Ψ(−x, −ẋ, −λ, −λ̇) = −Ψ(x, ẋ, λ, λ̇), so its partials are even. On a
  // basis of odd harmonics every input is half-wave antiperiodic
  // (q(t + T/2) = −q(t)); then so is Ψ, and the assembly evaluates the law on
  // the first half of the period only (FourierTransform's half-wave sampling).
  virtual bool oddSymmetric() const { return false; }
  // K > 0 for a history law (LawSamples): Ψ at a sample reads the
  // displacement over the whole period, with K terms per sample and pair of
  // components in its Jacobian besides the diagonal. Such a law is never
  // oddSymmetric (its period is not sampled by halves).
  virtual int historyTerms() const { return 0; }
  // K on a period of `samples` samples, for a law whose terms grow with the
  // period (a slider whose state reaches back over every sample); on one
  // sample it is historyTerms(). The sizes LawSamples::resize takes.
  virtual int historyTermsOn(int samples) const {
    static_cast<void>(samples);
    return historyTerms();
  }
  // True for rate-independent friction: its static step from the unloaded
  // state (preload/static_contact.h) reads the displacement increment as the
  // velocity and the force increment as the force rate (one implicit step of
  // unit length from rest: a contact sticks unless the static load makes it
  // slip). False: the law is seen at rest (velocity 0: a damper adds no
  // static force).
  virtual bool rateIndependent() const { return false; }
  // The law's state on one sample at rest (inputs filled as the static step
  // fills them); nullopt for a law that is not a contact or a friction.
  virtual std::optional<StaticStatus> staticStatus(const LawSamples& rest) const {
    static_cast<void>(rest);
    return std::nullopt;
  }
  // A law whose stuck state a periodic orbit cannot fix by itself (the
  // slider of an alternating frequency–time friction stays anywhere it
  // stuck): a copy anchored at the static state `rest` (one sample, as
  // staticStatus reads it), so that a period that never slips keeps the
  // slider where the static load left it. nullptr for laws without such a
  // state.
  virtual std::shared_ptr<Law> anchoredAt(const LawSamples& rest) const {
    static_cast<void>(rest);
    return nullptr;
  }
  // Fills psi and, if with_derivatives, the partials of the used inputs.
  virtual void evaluate(LawSamples& samples, bool with_derivatives) const = 0;
  // Physical checks on samples of a solution (inputs filled, densely in
  // time): named worst violations, 0 when the law holds exactly (see each
  // law for the measures). Truncated Fourier series only approach them.
  // Each measure is relative to the size of its channel on the samples, but
  // never to less than kInvariantScaleFloor of the problem's own scale
  // (`scales`): a channel that vanishes (a contact that is never pressed, a
  // friction that never slips) would otherwise turn solver noise of 1e-13
  // into a violation of order one.
  virtual std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                                 const PhysicalScales& scales) const = 0;
  // The exact (set-valued) law on one time step: the force λ over the step.
  // Regularised forms are ignored here: the reference is the exact law.
  virtual LocalVector solveStep(const StepProblem& step) const = 0;
  // For a law whose ρ is scale-free (RhoSetting::scaleFree), or whose
  // regularisation width is (none given): a copy with ρ and the width set
  // from `scales`; nullptr when the law has neither or was given both.
  virtual std::shared_ptr<Law> withScaleFreeRho(const LawScales& scales) const;
  // The ρ in use next to the scale-free ρ (factor 1) for `scales`, of the
  // law's first equation: what a failure blames on a badly scaled ρ.
  // nullopt for a law without ρ.
  struct RhoComparison {
    double in_use, scale_free;
  };
  virtual std::optional<RhoComparison> compareRho(const LawScales& scales) const;
  // For a regularised form whose width the scene left unset: the width in
  // use next to its scale-free value for `scales`
  // (kScaleFreeWidthFraction); withScaleFreeRho sets it with ρ. nullopt for
  // a law or form without a width.
  virtual std::optional<WidthComparison> compareWidth(const LawScales& scales) const;
};

// A law attached to the structure through a map W (law_attachment.h): a DOF
// list, 0-based and one per component, is the grounded form.
struct AttachedLaw {
  LawAttachment attachment;
  std::shared_ptr<Law> law;
};

}  // namespace eqhb
