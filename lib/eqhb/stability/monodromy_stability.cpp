#include "eqhb/stability/monodromy_stability.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/stability/multiplier_stability.h"
#include "eqhb/orbits/flow_dynamics.h"
#include "eqhb/orbits/shooting.h"

namespace eqhb {

namespace {

bool exactCoulomb(const Law& law) {
  const auto* c = dynamic_cast<const Coulomb1D*>(&law);
  return c && (c->form() == CoulombForm::kMinMax || c->form() == CoulombForm::kProjection);
}

// The fraction in [0, 1] of a sample interval where the linear interpolant
// of a quantity going from a to b vanishes (0.5 when it does not change).
double crossing(double a, double b) {
  const double d = a - b;
  if (d == 0.0 || !std::isfinite(a / d)) return 0.5;
  return std::clamp(a / d, 0.0, 1.0);
}

}  // namespace

bool MonodromyStability::supports(const HbModel& model) {
  if (model.laws.empty()) return false;
  for (const AttachedLaw& a : model.laws) {
    if (!a.attachment.grounded() || a.law->dimension() != 1) return false;
    if (!exactCoulomb(*a.law) && !dynamic_cast<const Signorini*>(a.law.get())) return false;
  }
  return true;
}

MonodromyStability::MonodromyStability(const HbModel& model, double unit_tolerance)
    : model_(model), unit_tolerance_(unit_tolerance) {
  model_.validate();
  if (!supports(model_))
    throwInputError("stability_method", "\"monodromy\"",
                    "needs grounded Coulomb 1D (minmax or projection form) or Signorini laws only; use hill");
  n_ = model_.structure.dofs();
  transform_ = std::make_unique<FourierTransform>(model_.basis, model_.samples);
  // The loads at the samples: harmonic h at t_k = kT/N has the phase
  // 2π h k / N whatever ω, so they are sampled once.
  load_samples_ = Eigen::MatrixXd::Zero(model_.samples, n_);
  for (const HarmonicLoad& load : model_.structure.loads)
    for (int k = 0; k < model_.samples; ++k) load_samples_(k, load.dof) += load.at(2.0 * M_PI * k / model_.samples);
  dynamics_ = orbits::DenseDynamics(model_.structure);  // throws unless M > 0
  for (const AttachedLaw& a : model_.laws) {
    dofs_.push_back(a.attachment.dof(0));
    if (const auto* c = dynamic_cast<const Coulomb1D*>(a.law.get())) {
      contact_.push_back(false);
      limit_.push_back(c->muN());
      rho_.push_back(c->form() == CoulombForm::kMinMax ? 1.0 / c->rho() : c->rho());
      gap_.push_back(0.0);
    } else {
      const auto* s = dynamic_cast<const Signorini*>(a.law.get());
      contact_.push_back(true);
      limit_.push_back(0.0);
      rho_.push_back(s->rho());
      gap_.push_back(s->gap());
    }
  }
}

MonodromyStability::~MonodromyStability() = default;

// Samples of each law's displacement, velocity and force, and its state per
// sample by the law's branch rule (header).
void MonodromyStability::classify(const Eigen::VectorXd& full) {
  const int nb = model_.basis.size(), samples = model_.samples, laws = static_cast<int>(dofs_.size());
  FourierTransform& transform = *transform_;
  u_.resize(samples, laws);
  v_.resize(samples, laws);
  r_.resize(samples, laws);
  Eigen::VectorXd rate(nb);
  for (int l = 0; l < laws; ++l) {
    const double* x = full.data() + dofs_[l] * nb;
    transform.synthesize(x, u_.col(l).data());
    transform.differentiate(x, model_.omega, rate.data());
    transform.synthesize(rate.data(), v_.col(l).data());
    transform.synthesize(full.data() + (n_ + model_.componentIndex(l, 0)) * nb, r_.col(l).data());
  }
  x_.resize(samples, n_);
  xdot_.resize(samples, n_);
  for (int i = 0; i < n_; ++i) {
    transform.synthesize(full.data() + i * nb, x_.col(i).data());
    transform.differentiate(full.data() + i * nb, model_.omega, rate.data());
    transform.synthesize(rate.data(), xdot_.col(i).data());
  }
  // f(t_k) − K x_k − C ẋ_k per sample, the part of every holding force's b
  // that does not depend on the states.
  base_force_ = load_samples_ - x_ * dynamics_.stiffness.transpose() - xdot_ * dynamics_.damping.transpose();
  states_.assign(samples, std::vector<State>(laws, State::kStick));
  for (int k = 0; k < samples; ++k)
    for (int l = 0; l < laws; ++l) {
      if (contact_[l]) {
        states_[k][l] = r_(k, l) > rho_[l] * (gap_[l] - u_(k, l)) ? State::kClosed : State::kOpen;
        continue;
      }
      const double trial = r_(k, l) - rho_[l] * v_(k, l);
      states_[k][l] = std::abs(trial) <= limit_[l] ? State::kStick
                      : trial < 0.0               ? State::kSlipPositive
                                                  : State::kSlipNegative;
    }
}

// A truncated series cannot jump, so the samples' states are checked by
// the exact rule on the model at the samples' displacements (with v = 0 at
// the held DOF). Through a reversal the series' force turns over a few
// samples inside ±μN and reads as a short stick: where a stick run starts,
// the force that holds the DOF, λ = −(P M⁻¹Pᵀ)⁻¹P M⁻¹ b, decides; |λ| > μN
// reverses at the run's zero of v instead. A stick that holds lasts while
// |λ| <= μN (the series' force rings near the limit and flickers there),
// then slips against λ until the samples slip the other way.
void MonodromyStability::addSlipForce(int l, State state, Eigen::VectorXd& b) const {
  if (state == State::kSlipPositive) b[dofs_[l]] -= limit_[l];
  if (state == State::kSlipNegative) b[dofs_[l]] += limit_[l];
}

double MonodromyStability::holdingForce(int l, int k) {
  // b = f(t_k) − K x − C v with the held DOF's velocity 0 (the rest of b_k
  // is sampled once per orbit in classify), plus the other laws' slip forces.
  const int held_dof = dofs_[l];
  force_ = base_force_.row(k).transpose() + dynamics_.damping.col(held_dof) * xdot_(k, held_dof);
  held_dofs_.clear();
  int row = 0;
  for (size_t m = 0; m < states_[k].size(); ++m) {
    const State state = static_cast<int>(m) == l ? State::kStick : states_[k][m];
    addSlipForce(static_cast<int>(m), state, force_);
    if (!held(state)) continue;
    if (static_cast<int>(m) == l) row = static_cast<int>(held_dofs_.size());
    held_dofs_.push_back(dofs_[m]);
  }
  auto found = multipliers_.find(held_dofs_);
  if (found == multipliers_.end())
    found = multipliers_.emplace(held_dofs_, orbits::holdDofs(dynamics_.mass_inverse, held_dofs_).multiplier).first;
  return found->second.row(row).dot(force_);
}

void MonodromyStability::keepHeldRuns() {
  const int samples = model_.samples, laws = static_cast<int>(dofs_.size());
  auto opposite = [](State s) { return s == State::kSlipPositive ? State::kSlipNegative : State::kSlipPositive; };
  for (int l = 0; l < laws; ++l) {
    if (contact_[l]) continue;
    int origin = 0;  // a slipping sample to scan from
    while (origin < samples && states_[origin][l] == State::kStick) ++origin;
    if (origin == samples) continue;
    const double sliding_scale = v_.col(l).cwiseAbs().maxCoeff();
    for (int i = 1; i <= samples; ++i) {
      const int first = (origin + i) % samples, before = (first + samples - 1) % samples;
      if (states_[first][l] != State::kStick || states_[before][l] == State::kStick) continue;
      // The run starts where v reaches 0 (the series' v rings into it).
      const State old_state = states_[before][l];
      const double sign = old_state == State::kSlipPositive ? 1.0 : -1.0;
      int zero = first;
      while (states_[zero][l] == State::kStick && sign * v_(zero, l) > 0.0 && zero != origin) zero = (zero + 1) % samples;
      if (states_[zero][l] != State::kStick || zero == origin) zero = first;
      for (int k = first; k != zero; k = (k + 1) % samples) states_[k][l] = old_state;
      const double force = holdingForce(l, zero);
      if (std::abs(force) > limit_[l]) {  // a reversal at v = 0
        for (int k = zero; states_[k][l] == State::kStick && k != origin; k = (k + 1) % samples)
          states_[k][l] = opposite(old_state);
        continue;
      }
      r_(zero, l) = force;
      const int start = zero;
      int k = (start + 1) % samples;
      for (; k != start; k = (k + 1) % samples) {
        r_(k, l) = holdingForce(l, k);
        if (std::abs(r_(k, l)) > limit_[l]) break;
        states_[k][l] = State::kStick;
      }
      // Slip against λ through the series' flicker, up to the first sample
      // that clearly slides (kSlidingFraction of max|v|).
      const State slip = r_(k, l) > 0.0 ? State::kSlipNegative : State::kSlipPositive;
      const double direction = slip == State::kSlipPositive ? 1.0 : -1.0;
      for (int j = k; j != start && states_[j][l] != opposite(slip); j = (j + 1) % samples) {
        if (direction * v_(j, l) > kSlidingFraction * sliding_scale) break;
        states_[j][l] = slip;
      }
    }
  }
}

// The instants where a law's state changes between two samples (the last
// sample wraps to the first), placed by linear interpolation of the
// quantity that vanishes there.
void MonodromyStability::findSwitches() {
  const int samples = model_.samples, laws = static_cast<int>(dofs_.size());
  const double step = 2.0 * M_PI / model_.omega / samples;
  switches_.clear();
  for (int k = 0; k < samples; ++k) {
    const int next = (k + 1) % samples;
    for (int l = 0; l < laws; ++l) {
      const State a = states_[k][l], b = states_[next][l];
      if (a == b) continue;
      double fraction = 0.5;
      if (a == State::kOpen) fraction = crossing(gap_[l] - u_(k, l), gap_[l] - u_(next, l));
      else if (a == State::kClosed) fraction = crossing(r_(k, l), r_(next, l));
      else if (a == State::kStick)
        fraction = crossing(std::abs(r_(k, l)) - limit_[l], std::abs(r_(next, l)) - limit_[l]);
      else fraction = crossing(v_(k, l), v_(next, l));
      switches_.push_back({(k + fraction) * step, l, a, b});
    }
  }
  std::stable_sort(switches_.begin(), switches_.end(), [](const Switch& x, const Switch& y) { return x.time < y.time; });
}

const Eigen::MatrixXd& MonodromyStability::generator(const std::vector<State>& states) {
  std::vector<bool> key(n_, false);
  for (size_t l = 0; l < states.size(); ++l) key[dofs_[l]] = key[dofs_[l]] || held(states[l]);
  auto found = generators_.find(key);
  if (found != generators_.end()) return found->second;
  std::vector<int> dofs;
  for (int i = 0; i < n_; ++i)
    if (key[i]) dofs.push_back(i);
  const Eigen::MatrixXd q = orbits::holdDofs(dynamics_.mass_inverse, dofs).projector;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n_, 2 * n_);
  a.topRightCorner(n_, n_).setIdentity();
  a.bottomLeftCorner(n_, n_) = -q * dynamics_.stiffness;
  a.bottomRightCorner(n_, n_) = -q * dynamics_.damping;
  projectors_[key] = q;
  return generators_[key] = a;
}

Eigen::VectorXd MonodromyStability::freeForce(const std::vector<State>& states, double t, const Eigen::VectorXd& y) const {
  Eigen::VectorXd b = -dynamics_.stiffness * y.head(n_) - dynamics_.damping * y.segment(n_, n_);
  for (const HarmonicLoad& load : model_.structure.loads) b[load.dof] += load.at(model_.omega * t);
  for (size_t l = 0; l < states.size(); ++l) addSlipForce(static_cast<int>(l), states[l], b);
  return b;
}

// [v; Q b] of the full forced system at (t, y) in `states`: b = f(t) − K x
// − C v + the slip forces; held DOFs take what their constraint needs.
Eigen::VectorXd MonodromyStability::field(const std::vector<State>& states, double t, const Eigen::VectorXd& y) {
  generator(states);
  std::vector<bool> key(n_, false);
  for (size_t l = 0; l < states.size(); ++l) key[dofs_[l]] = key[dofs_[l]] || held(states[l]);
  const Eigen::MatrixXd& q = projectors_.at(key);
  const Eigen::VectorXd b = freeForce(states, t, y);
  Eigen::VectorXd f(2 * n_);
  f.head(n_) = y.segment(n_, n_);
  for (int i = 0; i < n_; ++i)
    if (key[i]) f[i] = 0.0;
  f.tail(n_) = q * b;
  return f;
}

// S = R + (f⁺ − R f⁻) ∇gᵀ / ġ⁻ at switch s (header); I where the field is
// continuous (stick to slip, contact opening).
Eigen::MatrixXd MonodromyStability::saltation(const Switch& s, const std::vector<State>& before,
                                              const std::vector<State>& after, const Eigen::VectorXd& full) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Identity(2 * n_, 2 * n_);
  if (s.from == State::kStick || s.from == State::kClosed) return out;
  const int i = dofs_[s.law];
  Eigen::VectorXd y = orbits::harmonicState(model_, full, s.time).head(2 * n_);
  const bool slipping = s.from != State::kOpen;
  if (slipping) y[n_ + i] = 0.0;  // the event: the slip velocity vanishes
  Eigen::MatrixXd reset = Eigen::MatrixXd::Identity(2 * n_, 2 * n_);
  if (held(s.to)) reset(n_ + i, n_ + i) = 0.0;
  const int gradient = slipping ? n_ + i : i;  // g = v_i, or the gap's x_i (sign cancels)
  const Eigen::VectorXd f_before = field(before, s.time, y);
  const Eigen::VectorXd f_after = field(after, s.time, reset * y);
  const double rate = f_before[gradient];
  if (!(std::abs(rate) > 0.0) || !std::isfinite(rate)) return reset;
  out = reset;
  out.col(gradient) += (f_after - reset * f_before) / rate;
  return out;
}

HillResult MonodromyStability::analyse(double omega, const Eigen::VectorXd& full) {
  const auto start = std::chrono::steady_clock::now();
  if (!(omega > 0.0) || !std::isfinite(omega)) throwInputError("omega", formatNumber(omega), "must be finite and > 0");
  const int size = n_ * model_.basis.size() + model_.lawComponents() * model_.basis.size();
  if (full.size() != size)
    throwInputError("solution", std::to_string(full.size()) + " coefficients",
                    "must have " + std::to_string(size) + " ([x; lambda] of the full system)");
  model_.omega = omega;
  const double period = 2.0 * M_PI / omega;
  classify(full);
  keepHeldRuns();
  findSwitches();
  Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(2 * n_, 2 * n_);
  if (switches_.empty()) {
    phi = (generator(states_[0]) * period).exp();
  } else {
    // From just after the first switch round the period back to it.
    std::vector<State> current = states_[0];
    current[switches_[0].law] = switches_[0].to;
    for (size_t j = 0; j < switches_.size(); ++j) {
      const Switch& s = switches_[(j + 1) % switches_.size()];
      const double previous = switches_[j].time;
      const double tau = j + 1 < switches_.size() ? s.time - previous : s.time + period - previous;
      phi = (generator(current) * tau).exp() * phi;
      std::vector<State> after = current;
      after[s.law] = s.to;
      phi = saltation(s, current, after, full) * phi;
      current = after;
    }
  }
  HillResult result;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(phi, false);
  if (solver.info() != Eigen::Success) {
    result.method = "monodromy";
    result.state_dimension = result.candidates = result.pencil_size = 2 * n_;
    result.failure = "the eigenvalues of the monodromy matrix did not converge";
  } else {
    result = stabilityFromMultipliers(solver.eigenvalues(), period, unit_tolerance_, "monodromy");
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace eqhb
