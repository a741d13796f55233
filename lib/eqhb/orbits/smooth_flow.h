// Event-driven integration of a linear structure with laws that are smooth
// within each phase, for shooting:
//   M ẍ + C ẋ + K x = f(t) + Σ law forces,
// cubic stiffness (force −ε x³, no phases), planar Coulomb friction (slides
// with force −μN v/‖v‖, sticks while the force it needs stays in the disc
// ‖λ‖ <= μN) and Stribeck friction on one DOF (slides with force
// −L(|v|) sgn v, L(v) = μ_d N + (μ_s − μ_d) N exp(−|v|/v_s); sticks while
// |λ| <= μ_s N; Coulomb 1D is the case μ_s = μ_d, taken here when it is
// mixed with the laws above).
//
// Stuck DOFs G are held by the constraint force λ_G, as in the closed-form
// flow: with P their selection and b the other forces,
//   a = Q b,  Q = M⁻¹ − M⁻¹Pᵀ(P M⁻¹Pᵀ)⁻¹P M⁻¹,  λ_G = −(P M⁻¹Pᵀ)⁻¹P M⁻¹ b.
//
// Phases are integrated by the 3-stage Gauss–Legendre collocation method
// (order 6, A-stable), stages solved by Newton, with step-doubling error
// control (local error below kLocalTolerance of the state's scale). The
// Jacobian of each step is the exact derivative of the discrete map,
// dK = (I − h (A ⊗ J))⁻¹ J,  dy₁/dy₀ = I + h Σ b_i dK_i.
//
// Events that are sign changes of a smooth function g(t, y) (a Stribeck
// velocity through 0 on its smooth continuation; |λ| reaching the static
// limit; ‖λ‖ reaching μN) are bracketed at the half and end of every step
// and located by the Illinois method on the Gauss solution to round-off in
// t. A planar slide comes to rest differently: ‖v‖ reaches 0 linearly
// (d‖v‖/dt → ‖F‖ − μN < 0) and the sliding field is singular there, so it
// cannot be continued through; the steps are cut to 0.9 of the predicted
// time to rest ‖v‖ / (−d‖v‖/dt) until that time is below kRestTime of the
// time scale, and the rest instant is the linear extrapolation (its error is
// of second order in that time). At rest the exact Coulomb rule picks stick
// (‖λ‖ <= μN) or a new slide; a slide from rest starts in the direction of
// −λ, where the friction force μN λ̂ is continuous with the sticking force.
// At each event the Jacobian gets the saltation matrix
//   S = R + (f⁺ − R f⁻) ∇gᵀ / ġ
// (R zeroes the velocity rows of DOFs that stick; for rest g = ‖v‖,
// ∇g = v̂). Extremes of x_i and samples are taken by one Gauss step from the
// step start, as accurate as the steps themselves.
#pragma once

#include <map>
#include <memory>

#include "eqhb/orbits/piecewise_linear_flow.h"

namespace eqhb::orbits {

constexpr double kLocalTolerance = 1e-14;
// A planar slide predicted to reach rest within this fraction of the time
// scale (|t0| + T) is brought to rest.
constexpr double kRestTime = 1e-11;
// Speeds below this fraction of the velocity scale count as rest.
constexpr double kRestSpeed = 1e-14;

class SmoothFlow : public Flow {
 public:
  // Throws InputError unless every law is cubic, Coulomb 2D, Stribeck or
  // Coulomb 1D.
  explicit SmoothFlow(const HbModel& model);
  static bool supports(const HbModel& model);

  int stateSize() const override { return 2 * n_; }
  double period() const override { return 2.0 * M_PI / omega_; }
  FlowResult integrate(const Eigen::VectorXd& y0, double t0, double duration, bool with_jacobian,
                       FlowSamples* samples = nullptr) const override;

 private:
  class Integration;  // one call of integrate (smooth_flow_integration.h)
  enum class Kind { kCubic, kForce, kPlanar, kStribeck };
  enum class Mode { kSmooth, kSlide, kSlipPositive, kSlipNegative, kStick };
  using Modes = std::vector<Mode>;
  struct Site {
    Kind kind = Kind::kCubic;
    int dof = 0, second_dof = 0;
    double coefficient = 0.0;       // ε (cubic), μN (planar), μ_d N (Stribeck)
    double drop = 0.0, v_s = 1.0;   // Stribeck: (μ_s − μ_d) N and v_s
    std::function<void(double, double, double*, double*, double*)> force;  // kForce: f, ∂f/∂x, ∂f/∂ẋ
    // Always in smooth phase: no stick or slip of its own.
    bool alwaysSmooth() const { return kind == Kind::kCubic || kind == Kind::kForce; }
    int components() const { return kind == Kind::kPlanar ? 2 : 1; }
  };
  struct Constraint {
    std::vector<int> dofs;          // stuck DOFs, in site order
    std::vector<int> first_row;     // per site: its first row in λ_G, −1 if not stuck
    Eigen::MatrixXd projector;      // Q
    Eigen::MatrixXd multiplier;     // λ_G = multiplier · b
  };
  // A sign-change event: g(t, y) > 0 inside the phase.
  struct Watch {
    int site = 0;
    int branch = 0;  // Stribeck stick: +1 / −1 for μ_s N ∓ λ
    std::string kind;
  };

  const Constraint& constraint(const Modes& modes) const;
  void forcing(double t, Eigen::VectorXd& f, Eigen::VectorXd* df) const;
  // b = f(t) − K x − C v + the forces of laws that are not stuck, and ∂b/∂y;
  // false where a planar slide is at rest (its force is undefined there).
  bool freeForce(double t, const Eigen::VectorXd& y, const Modes& modes, Eigen::VectorXd& b,
                 Eigen::MatrixXd* db) const;
  bool field(double t, const Eigen::VectorXd& y, const Modes& modes, Eigen::VectorXd& dy,
             Eigen::MatrixXd* jacobian) const;
  // The force of site s on the structure (λ while stuck).
  Eigen::VectorXd siteForce(int s, double t, const Eigen::VectorXd& y, const Modes& modes) const;
  std::vector<Watch> watches(const Modes& modes) const;
  double eventValue(const Watch& w, double t, const Eigen::VectorXd& y, const Modes& modes,
                    Eigen::RowVectorXd* gradient, double* time_derivative) const;
  // Modes after site s came to rest at (t, y) (v of its DOFs = 0): exact
  // Coulomb rule with the static limit.
  Modes restModes(int s, double t, const Eigen::VectorXd& y, Modes modes) const;
  Modes initialModes(double t, const Eigen::VectorXd& y) const;
  // One Gauss step of size h from (t, y); dy1 = ∂y1/∂y if asked.
  bool step(double t, const Eigen::VectorXd& y, double h, const Modes& modes, Eigen::VectorXd& y1,
            Eigen::MatrixXd* dy1) const;
  // Stage guess for a step from a planar slide at rest: the friction force
  // saturated along the sticking force λ, the acceleration growing as the
  // excess ‖λ‖ − μN does.
  bool restartGuess(double t, const Eigen::VectorXd& y, const Modes& modes, Eigen::VectorXd& a0,
                    Eigen::VectorXd& jerk) const;

  int n_ = 0;
  double omega_ = 1.0, rate_ = 1.0;
  double acceleration_scale_ = 0.0;  // ‖M⁻¹‖ (Σ load amplitudes + friction limits)
  DenseDynamics dynamics_;  // M⁻¹, C, K
  std::vector<HarmonicLoad> loads_;
  std::vector<Site> sites_;
  int components_ = 0;
  mutable std::map<Modes, Constraint> constraints_;  // made once per mode set
};

// The flow for a model's laws: piecewise linear (Coulomb 1D, Signorini) or
// smooth phases (cubic, Coulomb 2D, Stribeck, and Coulomb 1D with those).
// Throws InputError for other laws or Signorini mixed with smooth laws.
std::unique_ptr<Flow> makeFlow(const HbModel& model, double restitution);

}  // namespace eqhb::orbits
