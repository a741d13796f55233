// Event-driven integration of a linear structure with exact Coulomb 1D
// friction, elastic dry friction on one DOF (Jenkins: spring k_t in series
// with a slider), Signorini contact (with Newton's impact law) and elastic
// walls (a penalty spring k_n pressed beyond g0), phase by phase in closed
// form.
//
// A Jenkins slider adds its position w to the state. Stuck, it is a spring:
// force −k_t (x − w) on its DOF, ẇ = 0, until |k_t (x − w)| reaches μN
// (event "slip"); slipping, the force is the constant ∓μN and ẇ = ẋ, until ẋ
// vanishes (the DOF turns back, the force leaves the limit inwards: "stick").
//
// Between events every law is in one mode — slip in +x or −x (constant force
// ∓μN), stick (velocity held at 0 by the force the structure needs, |r| <= μN),
// contact open (no force) or closed (gap held at 0, pressure p >= 0), an
// elastic wall open or pressed (force −k_n (x − g0), no constraint) — so
// the dynamics are linear with harmonic forcing. With G the constrained DOFs
// (stick, closed), P their selection and b = f(t) + s − C v − K x (s the
// sliding forces), the constrained acceleration and force are
//   a = Q b,   Q = M⁻¹ − M⁻¹Pᵀ (P M⁻¹ Pᵀ)⁻¹ P M⁻¹,   λ_G = −(P M⁻¹ Pᵀ)⁻¹ P M⁻¹ b.
// The state y = [x; v] is augmented with z = [y; 1; cos kωt; sin kωt ...]
// (one pair per forcing harmonic), whose generator Â is constant in a phase:
// z(t0 + τ) = exp(Â τ) z(t0), the homogeneous solution plus the harmonic and
// constant particular solutions in one matrix exponential (Van Loan's block
// form; Eigen's MatrixFunctions), valid even when K is singular or a forcing
// harmonic is resonant.
//
// Events are zeros of linear functionals g = cᵀ z (velocity of a sliding
// DOF, |r| − μN in stick, gap when open, pressure when closed, x − g0 when
// an elastic wall is pressed; its force is continuous there, so its
// saltation is the identity): bracketed on
// a grid finer than the fastest rate of the phase, then located by Newton
// with bisection safeguard to round-off in t. At an event the state is reset
// (impact: v⁺ = −e v⁻), the new modes chosen by the exact rules (a stopped
// DOF sticks iff the force it needs is within ±μN, else slips opposite to
// that force; a contact closes after a plastic impact iff the pressure it
// needs is >= 0), and the Jacobian gets the saltation matrix
//   S = R + (f⁺ − R f⁻) ∇gᵀ / ġ⁻
// (R the reset's Jacobian, f∓ the vector fields before/after, ġ⁻ = dg/dt).
#pragma once

#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/orbits/flow_dynamics.h"

namespace eqhb::orbits {

// Samples of one integrated interval at requested instants.
struct FlowSamples {
  std::vector<double> times;        // requested, increasing, inside the interval
  Eigen::MatrixXd displacement;     // times x n
  Eigen::MatrixXd velocity;         // times x n
  Eigen::MatrixXd force;            // times x law components (λ in the law's sign convention)
};

struct FlowResult {
  bool ok = false;
  std::string failure;              // why not ok
  Eigen::VectorXd end;              // y(t0 + duration) = [x; v]
  Eigen::MatrixXd jacobian;         // ∂ end / ∂ y0 (with saltation), if asked
  std::map<std::string, int> events;  // by kind: reversal, stick, slip, impact, release
  Eigen::VectorXd max_abs;          // max over the interval of |x_i|, located exactly
  int phases = 0;
};

// Smallest post-impact speed, relative to the impact speed, that still
// counts as a bounce: below it the impact is plastic (guards the
// accumulation of impacts of 0 < e < 1 at a finite time).
constexpr double kPlasticImpactRatio = 1e-10;

// A flow of the forced system over [t0, t0 + duration], with its Jacobian:
// what shooting needs, whatever integrates the phases.
class Flow {
 public:
  virtual ~Flow() = default;
  virtual int stateSize() const = 0;
  virtual double period() const = 0;
  virtual FlowResult integrate(const Eigen::VectorXd& y0, double t0, double duration, bool with_jacobian,
                               FlowSamples* samples = nullptr) const = 0;
};

class PiecewiseLinearFlow : public Flow {
 public:
  // Throws InputError when a law is not Coulomb 1D, Jenkins on 1 DOF,
  // Signorini or a penalty wall, or restitution e is outside [0, 1].
  PiecewiseLinearFlow(const HbModel& model, double restitution);

  // [x; v; w]: w the positions of the elastic (Jenkins) sliders, in law order.
  int stateSize() const override { return m_; }
  double period() const override { return 2.0 * M_PI / omega_; }
  // True if this flow can integrate the model's laws.
  static bool supports(const HbModel& model);

  // Integrates from y0 at t0 over `duration`. With `samples` (times set),
  // fills the samples. Modes at t0 follow from y0 by the same rules as at
  // events (a zero velocity or gap is tested for stick / closed contact).
  FlowResult integrate(const Eigen::VectorXd& y0, double t0, double duration, bool with_jacobian,
                       FlowSamples* samples = nullptr) const override;

 private:
  class Integration;  // one call of integrate (piecewise_linear_integration.h)
  enum class Mode { kSlipPositive, kSlipNegative, kStick, kOpen, kClosed };
  struct LawSite {
    bool contact = false;
    int dof = 0;
    double limit = 0.0;  // μN (friction)
    double gap = 0.0;    // g0 (contact)
    double stiffness = 0.0;  // k_t (elastic friction)
    double penalty = 0.0;    // k_n (elastic wall; kClosed: pressed)
    int slider = -1;         // index of the slider position w in the state, elastic friction only
  };
  struct Phase {
    Eigen::MatrixXd generator;       // Â
    Eigen::MatrixXd grid_step;       // exp(Â Δ)
    double grid = 0.0;               // Δ
    Eigen::MatrixXd constraint_force;  // rows: force on the structure at constrained DOFs, as cᵀ z
    std::vector<int> constrained;    // DOFs in G, order of rows above
  };
  struct Event {
    int law = -1;
    Eigen::RowVectorXd functional;   // g = cᵀ z, positive inside the phase
    std::string kind;
  };

  // The law holds its DOF in this mode (a constraint of the phase).
  static bool constrains(const LawSite& site, Mode mode);
  const Phase& phase(const std::vector<Mode>& modes) const;
  std::vector<Event> events(const std::vector<Mode>& modes, const Phase& p) const;
  std::vector<Mode> chooseModes(const Eigen::VectorXd& z, std::vector<Mode> modes,
                                const std::vector<bool>& free_choice) const;
  Eigen::VectorXd augment(const Eigen::VectorXd& y, double t) const;
  void refreshForcing(Eigen::VectorXd& z, double t) const;
  double lawForce(int l, Mode mode, const Phase& p, const Eigen::VectorXd& z) const;
  Eigen::RowVectorXd springForceRow(const LawSite& site) const;

  int n_ = 0, m_ = 0, nz_ = 0;  // DOFs, state size, augmented size
  double omega_ = 1.0, restitution_ = 0.0;
  DenseDynamics dynamics_;  // M⁻¹, C, K
  Eigen::VectorXd constant_load_;
  std::vector<int> harmonics_;                      // forcing harmonics k > 0
  std::vector<Eigen::VectorXd> cos_load_, sin_load_;  // per harmonic
  std::vector<LawSite> sites_;
  double rate_ = 1.0;                               // fastest rate of the model
  mutable std::map<std::vector<Mode>, Phase> phases_;  // made once per mode set
};

}  // namespace eqhb::orbits
