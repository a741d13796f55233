// Stability of a harmonic-balance solution of a nonsmooth law by the
// monodromy of the linearised dynamics over the known orbit, with saltation
// matrices at the law's switching instants.
//
// The orbit is the harmonic-balance solution; each law's state at each of
// its N samples is read from the solution's force and velocity (or gap) by
// the law's own branch rule: a Coulomb contact sticks where the trial force
// r − v/ρ (minmax; r − ρv for the projection form) lies inside ±μN, else it
// slips against v; a Signorini contact is closed where p > ρ g. Between two
// switching instants every law is in one state, and a perturbation y = [δx;
// δv] obeys the structure's homogeneous linear dynamics with the stuck or
// closed DOFs G held (a slip force and an open contact do not vary):
//   ẏ = A_G y,  A_G = [0 I; −Q K  −Q C],  Q = M⁻¹ − M⁻¹Pᵀ(P M⁻¹Pᵀ)⁻¹P M⁻¹,
// whose transition matrix over a phase of length τ is exactly exp(A_G τ).
// At a switching instant t* (between two samples, placed by linear
// interpolation of the quantity that vanishes there: v, |r| − μN, g or p)
// the perturbation gets the saltation matrix
//   S = R + (f⁺ − R f⁻) ∇gᵀ / ġ⁻
// (g the event function, f∓ the vector fields of the full forced system
// before and after at the harmonic-balance state y(t*), R the reset: the
// velocity of a DOF that sticks or closes plastically is held at 0). Slip
// to stick, a slip reversal (the force jumps by 2μN) and a contact closing
// have one; stick to slip and a contact opening are continuous (S = I).
// The monodromy Φ = Π S_j exp(A_G τ_j) over one period has the Floquet
// multipliers as its eigenvalues (2n of them). A truncated series cannot
// jump, so the samples' states are corrected by the exact rule on the model
// (keepHeldRuns). Measured at H = 20 against shooting: within 1e-4 of the
// exact radius where friction only reverses (friction-1d at ω = 0.55),
// 1.3e-3 on the Coulomb oscillator, but 0.009 and 0.018 off on friction-1d's
// stick–slip orbits at 0.308 and 0.4 (the stick onsets from the series'
// zero of v). Hill's method stays the reference; "auto" (the command line's
// default) takes this method wherever it applies.
//
// On odd harmonics with friction laws only (no contact: its gap is not
// odd), the orbit is half-wave antisymmetric, y(t + T/2) = −y(t), and so is
// the forced field, f(−y, t + T/2) = −f(y, t): the linearised dynamics and
// the saltations repeat every half period (a mirrored switch has f∓ and ġ⁻
// negated, the same S), so Φ = Φ_h² with Φ_h the transition over half a
// period. The states are read on the first half of the samples, sample
// k + N/2 being sample k with the slip directions swapped, and half the
// phases are propagated: half the passes and products a point, with the
// same multipliers (along the curves of every such scene the radii are
// within 1.7e-9 of the whole period's, 3e-12 on beam-damper's).
//
// Structures of more than MonodromyReduction::full_dofs (20) DOFs are
// propagated reduced to the law DOFs and the fixed-interface modes that are
// slow or weakly damped (interface_reduction.h): beam-damper's 120 DOFs
// become 6 (5 law DOFs and one mode), 0.11 ms a point against 1.2-1.6 s for
// the full 240 x 240 exponentials. The full propagation is no reference on
// such a beam: its stiff, heavily damped modes make the product depend on
// rounding (ω = 2.8: radius 0.956 in the physical coordinates, 0.830 in the
// reduced ones keeping every mode), while keeping the modes whose free
// multiplier is above e^-13.8, e^-30, e^-100, e^-1000 gives 0.2442, 0.2442,
// 0.2455, 0.2516. Hill's radius there is 0.499 on the whole beam (0.352
// on the modes within its band, hill_reduction.h); the time-domain orbit
// started from the harmonic-balance one settles at 0.196 a period (periods
// 2 to 12), which the reduced radius matches and 0.499 does not (tested).
// The holding forces stay on the full structure (M⁻¹ on the held DOFs'
// columns, solved from M's sparse factor). The reduction runs on the sparse
// matrices, and the propagation carries its product in the phases' leading
// modes (chainLeadingModes) wherever their generators are decomposed:
// beam-joint-large (2000 DOFs, 50 laws; 52 propagated DOFs) spends 20 ms
// setting up and ~5 ms a point, where the dense set-up took 11 s and the
// whole products ~60 ms a point; on beam-damper's 6 it is 20 % less time a
// point than the whole products (two 12 x 12 products a phase).
//
// Supported: grounded Coulomb 1D in an exact form (minmax, projection) and
// Signorini laws, one DOF each, with a positive definite mass (the phases
// are ODEs); or, all laws of a model of this other kind, penalty contact and
// Jenkins (exact, or AFT with one slider) on one relative coordinate each,
// and elastic friction with one tangent on its normal and tangential ones,
// grounded or between two nodes (spring_law_monodromy.h: the reduction then
// keeps the coordinates the laws read, a joint's relative motions, where
// holding them holds the structure, else every DOF an attachment touches).
// On the lap joint that is 42 relative coordinates and 9-10 modes instead of
// 84 DOFs and 8 modes: generators of ~104 rows instead of ~184, 4.4 times
// less stability time along its curve. The reductions' own error there, in
// microslip: radius within 3.4e-3 of the unreduced propagation's (the DOF
// boundary's 2.6e-3; 1.6e-4 keeping the modes down to e^-100, 2.6e-5 to
// e^-1000), well below what H = 7 leaves in the orbit itself (the
// time-domain rate is 8 % away). Everything else is Hill's (supports()). On the lap joint (180 DOFs, 42 such laws between nodes) the
// verdicts are Hill's where the joint sticks (radius within 1e-6) but not in
// microslip, where Hill's method finds radii 1.01-1.12 and the monodromy
// 0.91-0.98; there the time-domain orbit settles (tests).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/orbits/flow_dynamics.h"
#include "eqhb/stability/hill_stability.h"
#include "eqhb/stability/interface_reduction.h"
#include "eqhb/stability/phase_exponential.h"

namespace eqhb {

class FourierTransform;
class SpringLawMonodromy;

// Where the propagation is reduced (interface_reduction.h); the defaults
// are what every stability analysis uses, other values are for measuring
// the reduction against the full structure.
struct MonodromyReduction {
  int full_dofs = 20;    // structures of more DOFs are propagated reduced
  double decay = 13.8;   // a fast mode is dropped when its free multiplier is below e^-decay
  // The spring laws' reduction keeps the coordinates the laws read (a
  // joint's relative motions), else the DOFs they touch.
  bool law_coordinates = true;
  // The product is carried in the phases' leading modes where their
  // generators are decomposed, else (or false) the whole Φ.
  bool leading_modes = true;
  // On odd harmonics with friction only, half a period is propagated
  // (Φ = Φ_h², header), else the whole.
  bool half_period = true;
};

class MonodromyStability {
 public:
  // Throws InputError if the model is invalid or not supported.
  explicit MonodromyStability(const HbModel& model, double unit_tolerance = HillOptions().unit_tolerance,
                              const MonodromyReduction& reduction = MonodromyReduction());
  ~MonodromyStability();
  MonodromyStability(const MonodromyStability&) = delete;
  MonodromyStability& operator=(const MonodromyStability&) = delete;
  // True when every law is one the monodromy can follow (header).
  static bool supports(const HbModel& model);
  // Throws InputError if ω is not finite and > 0 or `full` has the wrong size.
  HillResult analyse(double omega, const Eigen::VectorXd& full);

  // Work counters since construction, a cost signal for tests: the FFT
  // syntheses of the orbit's samples, the holding forces evaluated, and the
  // matrix exponentials formed.
  struct Work {
    long syntheses = 0, holding_forces = 0, exponentials = 0;
  };
  const Work& work() const { return work_; }
  // The propagation's DOFs: the structure's, or the reduced coordinates.
  int propagatedDofs() const { return m_; }

 private:
  enum class State : std::uint8_t { kSlipPositive, kSlipNegative, kStick, kOpen, kClosed };
  struct Switch {
    double time = 0.0;
    int law = 0;
    State from = State::kStick, to = State::kStick;
  };
  // The holding force of law `law` under the held DOFs of one key, as a
  // function of time: multiplier row · b(t) with b's loads sampled once
  // (they do not depend on ω) and its orbit part a Fourier series formed per
  // point from the coefficients (the structure's DOFs are not sampled one by
  // one). The first sample asked for is summed from the series; a second one
  // samples the whole series by one synthesis (a stick run), so that a key
  // asked once a point (a reversal read through the series' ringing, all
  // beam-damper's) costs no transform.
  struct Holding {
    Eigen::RowVectorXd row;        // the multiplier's row of λ_law
    Eigen::VectorXd stiffness_row; // Kᵀ row
    Eigen::VectorXd damping_row;   // Cᵀ row, the held DOF's entry 0 (its velocity is held at 0)
    Eigen::VectorXd loads;         // row · f(t_k) per sample
    Eigen::VectorXd series;        // the orbit part's coefficients at the current point
    Eigen::VectorXd samples;       // row · b(t_k) but the slip forces, at the current point once sampled
    long point = -1;               // the point `series` belongs to
    bool sampled = false;          // `samples` holds this point's
    int first = -1;                // the sample summed from the series, and its value
    double first_value = 0.0;
  };
  // The projector Q for one set of held DOFs and its generator A_G's
  // exponential, decomposed once per curve.
  struct Phase {
    Eigen::MatrixXd projector;
    PhaseExponential exponential;
  };
  State& state(int k, int l) { return states_[static_cast<size_t>(k) * laws_ + l]; }
  State state(int k, int l) const { return states_[static_cast<size_t>(k) * laws_ + l]; }
  // A sample of the whole period, k in [0, N), on the stored span
  // [0, span_): past the span it is sample k − span_ mirrored (half-period
  // mode; in whole-period mode span_ = N and nothing is mirrored).
  struct Folded {
    int index;
    bool mirrored;
  };
  Folded fold(int k) const { return k < span_ ? Folded{k, false} : Folded{k - span_, true}; }
  static State mirror(State s) {
    return s == State::kSlipPositive ? State::kSlipNegative : s == State::kSlipNegative ? State::kSlipPositive : s;
  }
  void mirrorStates(std::vector<State>& states) const;
  void completePeriod(double* samples) const;
  void synthesize(const double* coefficients, double* samples);
  void classify(const Eigen::VectorXd& full);
  void keepHeldRuns(const Eigen::VectorXd& full);
  double holdingForce(const Eigen::VectorXd& full, int law, int sample);
  // b gains law l's slip force in `state` (∓μN against the slip; none held).
  void addSlipForce(int l, State state, Eigen::VectorXd& b) const;
  void findSwitches();
  // The propagation over the span from just after the first switch back to
  // it: Φ, or Φ_h in half-period mode.
  void propagateSpan(double span);
  // The verdict from the multipliers, the eigenvalues of phi (their
  // squares in half-period mode: phi is Φ_h).
  HillResult multipliers(const Eigen::MatrixXd& phi, double period, std::chrono::steady_clock::time_point start);
  // The verdict from the multipliers themselves (none: their eigenproblem failed).
  HillResult verdict(const Eigen::VectorXcd& multipliers, double period,
                     std::chrono::steady_clock::time_point start) const;
  const Phase& phase(const std::vector<State>& states);
  std::optional<LawCoordinateReduction> reduceOnLawCoordinates(double fast_rate, double period, double decay,
                                                               std::vector<Eigen::VectorXd>& law_directions) const;
  std::vector<Eigen::VectorXd> springLawDirections() const;
  const Eigen::VectorXd& massInverseColumn(int dof);
  // f = [v; Q b] of the forced system at (t, y) in `states`.
  void field(const std::vector<State>& states, double t, const Eigen::VectorXd& y, Eigen::VectorXd& f);
  void projectCoefficients(const Eigen::VectorXd& full);
  void orbitState(double t, Eigen::VectorXd& y) const;
  void applySaltation(const Switch& s, const std::vector<State>& before, const std::vector<State>& after,
                      Eigen::MatrixXd& phi);
  // multipliers_ from the product in the phases' leading modes (large
  // propagations); false where a phase is not decomposed.
  bool chainLeadingModes(double span);
  static bool held(State s) { return s == State::kStick || s == State::kClosed; }

  HbModel model_;
  std::unique_ptr<FourierTransform> transform_;
  double unit_tolerance_;
  int n_ = 0;
  long point_ = 0;                                 // analyses so far: stamps Holding::series
  Work work_;
  // The phases' decompositions kept at most (a cache; holdings 16 times as many).
  static constexpr size_t kMaxCachedSets = 256;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> mass_factor_;  // M of the full structure (holding forces)
  std::map<int, Eigen::VectorXd> mass_inverse_columns_;             // M⁻¹'s column per held DOF met
  int m_ = 0;                                      // the propagation's DOFs (n, or the reduced q's)
  Eigen::MatrixXd projection_;                     // q = P x (empty when not reduced)
  orbits::DenseDynamics propagated_;               // the propagation's M⁻¹, C, K (m x m)
  Eigen::MatrixXd load_directions_;                // Tᵀ: column j is DOF j's load in q
  std::vector<int> coords_;                        // per law: its DOF's coordinate in the propagation
  std::vector<int> dofs_;                          // per law
  int laws_ = 0;                                   // dofs_.size(): the held-DOF method's laws
  bool half_period_ = false;                       // odd harmonics, friction only: Φ = Φ_h² (header)
  int span_ = 0;                                   // samples read: N/2 in half-period mode, else N
  std::vector<double> limit_, rho_, gap_;          // per law: μN (friction), ρ in trial form, g0 (contact)
  std::vector<bool> contact_;
  Eigen::MatrixXd u_, v_, r_;                      // span x laws: displacement (contacts), velocity, force samples
  Eigen::VectorXd rate_, combined_;                // coefficient buffers (one channel)
  Eigen::MatrixXd load_samples_;                   // N x n: f(t_k), the same at every ω (t_k = kT/N)
  std::vector<int> held_key_;                      // holdingForce's held DOFs and the law's row, kept to allocate once
  std::map<std::vector<int>, Holding> holdings_;   // by held DOFs + row
  std::vector<int> last_key_;                      // the key of
  Holding* last_holding_ = nullptr;                // the last holding looked up
  std::uint64_t last_mask_ = 0;                    // its held laws (up to 64) and
  int last_law_ = -1;                              // its law
  std::vector<State> states_;                      // span x laws, row-major by sample
  std::vector<State> current_, after_;             // the propagation's states before and after a switch
  std::vector<bool> phase_key_;                    // phase()'s held DOFs, likewise
  std::vector<Switch> switches_;                   // increasing in time, within [0, T) (half-period: [0, T/2))
  std::map<std::vector<bool>, Phase> phases_;      // by held DOFs
  // Storage reused from point to point: the monodromy and a product's
  // scratch, the orbit's state at a switch (propagation), the
  // fields before and after it, Φ's row along the event's gradient, b.
  Eigen::MatrixXd phi_, scratch_;
  // chainLeadingModes: per phase its states, phase, length and kept modes;
  // the product in a phase's modes and in [q; q̇]; the multipliers.
  std::vector<std::vector<State>> phase_states_;
  std::vector<const Phase*> phase_refs_;
  std::vector<double> phase_length_;
  std::vector<Eigen::Index> kept_;
  Eigen::MatrixXd modal_, physical_;
  Eigen::VectorXcd multipliers_;
  Eigen::EigenSolver<Eigen::MatrixXd> eigen_;      // the multipliers' eigenproblem, its storage kept
  bool leading_modes_ = true;                      // MonodromyReduction::leading_modes
  Eigen::MatrixXd projected_;                      // nb x m: the orbit's coefficients in q (reduced)
  const double* orbit_coefficients_ = nullptr;     // nb x m, column-major: projected_ or the solution's x
  Eigen::VectorXd y_, f_before_, f_after_, force_;
  Eigen::RowVectorXd gradient_row_;
  std::unique_ptr<SpringLawMonodromy> springs_;    // penalty contact, Jenkins and elastic-friction laws (its header)
};

}  // namespace eqhb
