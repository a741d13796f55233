#include "eqhb/stability/monodromy_stability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/stability/interface_reduction.h"
#include "eqhb/stability/multiplier_stability.h"
#include "eqhb/stability/switch_crossing.h"
#include "eqhb/stability/spring_law_monodromy.h"
#include "eqhb/orbits/flow_dynamics.h"
#include "eqhb/orbits/shooting.h"

namespace eqhb {

namespace {

bool exactCoulomb(const Law& law) {
  const auto* c = dynamic_cast<const Coulomb1D*>(&law);
  return c && (c->form() == CoulombForm::kMinMax || c->form() == CoulombForm::kProjection);
}

}  // namespace

bool MonodromyStability::supports(const HbModel& model) {
  if (model.laws.empty()) return false;
  if (SpringLawMonodromy::supports(model)) return true;
  for (const AttachedLaw& a : model.laws) {
    if (!a.attachment.grounded() || a.law->dimension() != 1) return false;
    if (!exactCoulomb(*a.law) && !dynamic_cast<const Signorini*>(a.law.get())) return false;
  }
  return true;
}

MonodromyStability::MonodromyStability(const HbModel& model, double unit_tolerance,
                                       const MonodromyReduction& reduction)
    : model_(model), unit_tolerance_(unit_tolerance), leading_modes_(reduction.leading_modes) {
  model_.validate();
  if (!supports(model_))
    throwInputError("stability_method", "\"monodromy\"",
                    "needs grounded Coulomb 1D (minmax or projection form) or Signorini laws only, or penalty "
                    "contact and jenkins laws on one coordinate (exact, or aft with one slider) and "
                    "elastic-friction with one tangent only; use hill");
  n_ = model_.structure.dofs();
  // On odd harmonics the second half-period is the first's negative:
  // half the samples are transformed (synthesize).
  transform_ = std::make_unique<FourierTransform>(model_.basis, model_.samples, Sampling::kHalfWave);
  // The loads at the samples: harmonic h at t_k = kT/N has the phase
  // 2π h k / N whatever ω, so they are sampled once.
  load_samples_ = Eigen::MatrixXd::Zero(model_.samples, n_);
  for (const HarmonicLoad& load : model_.structure.loads)
    for (int k = 0; k < model_.samples; ++k) load_samples_(k, load.dof) += load.at(2.0 * M_PI * k / model_.samples);
  rate_.resize(model_.basis.size());
  combined_.resize(model_.basis.size());
  // M⁻¹ is needed on the held DOFs' columns only (holdingForce): the mass
  // is factorised sparse and the columns solved for as they are met.
  mass_factor_.compute(model_.structure.mass);
  if (mass_factor_.info() != Eigen::Success)
    throwInputError("structure.mass", "singular", "exact orbits need a positive definite mass (no massless DOFs)");
  const bool springs = SpringLawMonodromy::supports(model_);
  // The DOFs kept by a reduction: every DOF an attachment touches.
  std::vector<int> boundary;
  for (const AttachedLaw& a : model_.laws)
    for (int dof : a.attachment.dofs()) boundary.push_back(dof);
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  // The held-DOF method's sites: one grounded DOF per law (none when the
  // spring laws' method runs).
  if (!springs)
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
  laws_ = static_cast<int>(dofs_.size());
  // Half a period is enough where the series and the field are odd in it
  // (header): odd harmonics (the transform samples half; the loads are on
  // the model's harmonics, validated), friction only.
  half_period_ = reduction.half_period && !springs && transform_->activeSamples() < model_.samples &&
                 std::none_of(contact_.begin(), contact_.end(), [](bool contact) { return contact; });
  span_ = half_period_ ? transform_->activeSamples() : model_.samples;
  // The propagation's structure: the full one on small structures, else
  // reduced to the law DOFs and the modes that matter (interface_reduction.h);
  // the spring laws' on the coordinates they read where that holds the
  // structure (a joint's relative motions: half its DOFs).
  std::vector<Eigen::VectorXd> law_directions;  // the spring laws': per law, w in q
  if (n_ > reduction.full_dofs) {
    int k_max = 1;
    for (int k : model_.basis.harmonics()) k_max = std::max(k_max, k);
    const double fast_rate = kResolvedBandMargin * k_max * model_.omega, period = 2.0 * M_PI / model_.omega;
    std::optional<LawCoordinateReduction> by_law;
    if (springs && reduction.law_coordinates)
      by_law = reduceOnLawCoordinates(fast_rate, period, reduction.decay, law_directions);
    const LinearStructure& s = model_.structure;
    const InterfaceReduction reduced =
        by_law ? by_law->reduction
               : reduceToInterface(s.mass, s.damping, s.stiffness, boundary, fast_rate, period, reduction.decay);
    m_ = static_cast<int>(reduced.mass.rows());
    projection_ = reduced.projection;
    propagated_.mass_inverse = reduced.mass.inverse();
    propagated_.damping = reduced.damping;
    propagated_.stiffness = reduced.stiffness;
    for (int dof : dofs_)  // reduced.boundary is `boundary`, sorted
      coords_.push_back(static_cast<int>(std::lower_bound(reduced.boundary.begin(), reduced.boundary.end(), dof) -
                                         reduced.boundary.begin()));
    load_directions_ = reduced.basis.transpose();
    if (springs && !by_law)  // u = wᵀx = (Tᵀw)ᵀq: w's weights at its DOFs' places in the boundary
      for (const Eigen::VectorXd& w : springLawDirections()) law_directions.push_back(load_directions_ * w);
  } else {
    m_ = n_;
    propagated_ = orbits::DenseDynamics(model_.structure);
    coords_ = dofs_;
    load_directions_ = Eigen::MatrixXd::Identity(n_, n_);
    if (springs) law_directions = springLawDirections();
  }
  if (springs)
    springs_ = std::make_unique<SpringLawMonodromy>(model_, propagated_.mass_inverse, propagated_.damping,
                                                    propagated_.stiffness, law_directions);
}

// The reduction on the spring laws' coordinates (interface_reduction.h):
// their distinct directions (a law on −w or 2w reads the same coordinate),
// and per law its w in q, a multiple of a unit vector there. Empty when the
// directions are dependent or the structure needs its joints to be held
// (the DOF boundary is used then).
std::optional<LawCoordinateReduction> MonodromyStability::reduceOnLawCoordinates(
    double fast_rate, double period, double decay, std::vector<Eigen::VectorXd>& law_directions) const {
  std::vector<Eigen::VectorXd> distinct;
  std::vector<std::pair<int, double>> along;  // per law: its direction and the factor w = c w_j
  for (const Eigen::VectorXd& w : springLawDirections()) {
    int found = -1;
    double factor = 1.0;
    for (size_t j = 0; j < distinct.size() && found < 0; ++j) {
      factor = distinct[j].dot(w) / distinct[j].squaredNorm();
      if ((w - factor * distinct[j]).norm() <= 1e-12 * w.norm()) found = static_cast<int>(j);
    }
    if (found < 0) {
      found = static_cast<int>(distinct.size());
      factor = 1.0;
      distinct.push_back(w);
    }
    along.push_back({found, factor});
  }
  Eigen::MatrixXd directions(n_, static_cast<Eigen::Index>(distinct.size()));
  for (size_t j = 0; j < distinct.size(); ++j) directions.col(static_cast<Eigen::Index>(j)) = distinct[j];
  std::optional<LawCoordinateReduction> out;
  try {
    const LinearStructure& s = model_.structure;
    out = reduceToLawCoordinates(Eigen::MatrixXd(s.mass), Eigen::MatrixXd(s.damping), Eigen::MatrixXd(s.stiffness),
                                 directions, fast_rate, period, decay);
  } catch (const InputError&) {
    return std::nullopt;  // held by its joints alone
  }
  if (!out) return out;
  const Eigen::Index m = out->reduction.mass.rows();
  law_directions.clear();
  for (const auto& [j, factor] : along) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(m);
    w[out->coordinate[j]] = factor;
    law_directions.push_back(w);
  }
  return out;
}

// Per spring law and component, in order, the w of u = wᵀx (one per
// SpringLawMonodromy channel).
std::vector<Eigen::VectorXd> MonodromyStability::springLawDirections() const {
  std::vector<Eigen::VectorXd> out;
  for (const AttachedLaw& a : model_.laws) {
    const Eigen::MatrixXd w = a.attachment.transposeDense(n_);
    for (Eigen::Index c = 0; c < w.cols(); ++c) out.push_back(w.col(c));
  }
  return out;
}

MonodromyStability::~MonodromyStability() = default;

// All N samples from a half-wave transform's N/2: x(t + T/2) = −x(t) on
// odd harmonics (nothing to do on a full-period transform).
void MonodromyStability::completePeriod(double* samples) const {
  const int half = transform_->activeSamples();
  for (int k = half; k < model_.samples; ++k) samples[k] = -samples[k - half];
}

void MonodromyStability::synthesize(const double* coefficients, double* samples) {
  transform_->synthesize(coefficients, samples);
  completePeriod(samples);
}

// Samples of each law's velocity, force (and displacement for contacts),
// and its state per sample by the law's branch rule (header). The
// structure's other DOFs are not sampled: the holding forces are series
// formed from the coefficients (holdingForce).
void MonodromyStability::classify(const Eigen::VectorXd& full) {
  const int nb = model_.basis.size(), samples = span_, laws = laws_;
  FourierTransform& transform = *transform_;
  // A half-wave transform fills N/2 samples: the whole period's mode
  // completes them, half-period mode reads those alone.
  u_.resize(model_.samples, laws);
  v_.resize(model_.samples, laws);
  r_.resize(model_.samples, laws);
  for (int l = 0; l < laws; ++l) {
    const double* x = full.data() + dofs_[l] * nb;
    if (contact_[l]) {
      synthesize(x, u_.col(l).data());
      ++work_.syntheses;
    }
    transform.differentiate(x, model_.omega, rate_.data());
    transform.synthesizePair(rate_.data(), full.data() + (n_ + model_.componentIndex(l, 0)) * nb, v_.col(l).data(),
                             r_.col(l).data());
    if (!half_period_) {
      completePeriod(v_.col(l).data());
      completePeriod(r_.col(l).data());
    }
    work_.syntheses += 2;
  }
  states_.resize(static_cast<size_t>(samples) * laws);
  for (int l = 0; l < laws; ++l) {
    const double *u = u_.col(l).data(), *v = v_.col(l).data(), *r = r_.col(l).data();
    const double rho = rho_[l], gap = gap_[l], limit = limit_[l];
    State* out = states_.data() + l;
    if (contact_[l]) {
      for (int k = 0; k < samples; ++k) out[k * laws] = r[k] > rho * (gap - u[k]) ? State::kClosed : State::kOpen;
      continue;
    }
    for (int k = 0; k < samples; ++k) {
      const double trial = r[k] - rho * v[k];
      out[k * laws] = std::abs(trial) <= limit ? State::kStick
                      : trial < 0.0           ? State::kSlipPositive
                                              : State::kSlipNegative;
    }
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
  if (state == State::kSlipPositive) b[coords_[l]] -= limit_[l];
  if (state == State::kSlipNegative) b[coords_[l]] += limit_[l];
}

// λ = row · b(t_k) with b = f − K x − C ẋ (the held DOF's velocity 0) plus
// the other laws' slip forces. Per (held DOFs, law) the row, Kᵀrow, Cᵀrow
// and the loads' part are made once per curve; the orbit's part is the
// series −(Kᵀrow)·X − D((Cᵀrow)·X), formed (O(n nb)) and sampled once per
// point, so that a stick run costs one synthesis, not n per sample.
double MonodromyStability::holdingForce(const Eigen::VectorXd& full, int l, int k) {
  ++work_.holding_forces;
  const int held_dof = dofs_[l], nb = model_.basis.size(), samples = model_.samples;
  const int laws = laws_;
  // Consecutive calls mostly ask for the same key (a stick run): up to 64
  // laws, the held laws' bit mask and l name it without building it.
  std::uint64_t mask = 0;
  if (laws <= 64)
    for (int m = 0; m < laws; ++m)
      if (m == l || held(state(k, m))) mask |= std::uint64_t{1} << m;
  const bool same = last_holding_ != nullptr && laws <= 64 && mask == last_mask_ && l == last_law_;
  if (!same) {
    held_key_.clear();
    int row = 0;
    for (int m = 0; m < laws; ++m) {
      const State s = m == l ? State::kStick : state(k, m);
      if (!held(s)) continue;
      if (m == l) row = static_cast<int>(held_key_.size());
      held_key_.push_back(dofs_[m]);
    }
    held_key_.push_back(row);
    last_mask_ = mask;
    last_law_ = l;
  }
  if (!same && (last_holding_ == nullptr || last_key_ != held_key_)) {
    auto found = holdings_.find(held_key_);
    if (found == holdings_.end()) {
      Holding h;
      // The multiplier's row alone: −e_rowᵀ (P M⁻¹ Pᵀ)⁻¹ P M⁻¹, O(g n) with
      // g held DOFs, not the projector's O(n² g).
      const int g = static_cast<int>(held_key_.size()) - 1;
      Eigen::MatrixXd coupling(g, g), pm(g, n_);
      for (int a = 0; a < g; ++a) {
        const Eigen::VectorXd& column = massInverseColumn(held_key_[a]);  // = its row: M⁻¹ is symmetric
        pm.row(a) = column.transpose();
        for (int b = 0; b < g; ++b) coupling(b, a) = column[held_key_[b]];
      }
      const Eigen::VectorXd pick = coupling.ldlt().solve(Eigen::VectorXd::Unit(g, held_key_.back()));  // coupling is symmetric
      h.row = -(pick.transpose() * pm);
      h.stiffness_row = model_.structure.stiffness.transpose() * h.row.transpose();
      h.damping_row = model_.structure.damping.transpose() * h.row.transpose();
      h.damping_row[held_dof] = 0.0;
      h.loads = load_samples_ * h.row.transpose();
      h.samples.resize(samples);
      found = holdings_.emplace(held_key_, std::move(h)).first;
    }
    last_holding_ = &found->second;
    last_key_ = held_key_;
  }
  Holding& h = *last_holding_;
  if (h.point != point_) {
    // −(Kᵀrow)·X − D((Cᵀrow)·X) as a series.
    const Eigen::Map<const Eigen::MatrixXd> x(full.data(), nb, n_);
    combined_.noalias() = x * h.damping_row;
    differentiateCoefficients(model_.basis, combined_.data(), model_.omega, rate_.data());
    h.series.noalias() = -(x * h.stiffness_row);
    h.series -= rate_;
    h.point = point_;
    h.sampled = false;
    h.first = -1;
  }
  double force = 0.0;
  if (h.sampled) {
    force = h.samples[k];
  } else if (h.first < 0 || h.first == k) {
    if (h.first < 0) {
      h.first = k;
      h.first_value = seriesAt(model_.basis, h.series.data(), 2.0 * M_PI * k / samples).value + h.loads[k];
    }
    force = h.first_value;
  } else {
    transform_->synthesize(h.series.data(), h.samples.data());
    if (!half_period_) completePeriod(h.samples.data());
    ++work_.syntheses;
    h.samples.head(span_) += h.loads.head(span_);  // the samples read (half-period mode: the first half)
    h.sampled = true;
    force = h.samples[k];
  }
  for (int m = 0; m < laws; ++m) {
    if (m == l) continue;
    const State s = state(k, m);
    if (s == State::kSlipPositive) force -= h.row[dofs_[m]] * limit_[m];
    if (s == State::kSlipNegative) force += h.row[dofs_[m]] * limit_[m];
  }
  return force;
}

const Eigen::VectorXd& MonodromyStability::massInverseColumn(int dof) {
  auto found = mass_inverse_columns_.find(dof);
  if (found != mass_inverse_columns_.end()) return found->second;
  return mass_inverse_columns_.emplace(dof, mass_factor_.solve(Eigen::VectorXd::Unit(n_, dof))).first->second;
}

// Over the whole period, k in [0, N), through fold(): in half-period mode
// a run that crosses T/2 goes on in the stored half mirrored, and only the
// runs that start in one half-period's worth of samples are walked.
void MonodromyStability::keepHeldRuns(const Eigen::VectorXd& full) {
  const int samples = model_.samples, laws = laws_;
  auto next = [samples](int k) { return k + 1 == samples ? 0 : k + 1; };  // round the period
  auto opposite = [](State s) { return s == State::kSlipPositive ? State::kSlipNegative : State::kSlipPositive; };
  for (int l = 0; l < laws; ++l) {
    if (contact_[l]) continue;
    // Stuck or not does not depend on the mirror: the scan reads the stored state.
    auto stuck = [&](int k) { return state(fold(k).index, l) == State::kStick; };
    auto stateAt = [&](int k) {
      const Folded f = fold(k);
      return f.mirrored ? mirror(state(f.index, l)) : state(f.index, l);
    };
    auto setState = [&](int k, State s) {
      const Folded f = fold(k);
      state(f.index, l) = f.mirrored ? mirror(s) : s;
    };
    auto velocity = [&](int k) {
      const Folded f = fold(k);
      return f.mirrored ? -v_(f.index, l) : v_(f.index, l);
    };
    auto force = [&](int k) {
      const Folded f = fold(k);
      return f.mirrored ? -r_(f.index, l) : r_(f.index, l);
    };
    // λ at sample k, kept as the sample's force.
    auto hold = [&](int k) {
      const Folded f = fold(k);
      const double held = holdingForce(full, l, f.index);
      r_(f.index, l) = held;
      return f.mirrored ? -held : held;
    };
    int origin = 0;  // a slipping sample to scan from
    while (origin < span_ && state(origin, l) == State::kStick) ++origin;
    if (origin == span_) continue;
    const double sliding_scale = v_.col(l).head(span_).cwiseAbs().maxCoeff();
    for (int i = 1; i <= span_; ++i) {
      const int first = origin + i < samples ? origin + i : origin + i - samples;
      const int before = first == 0 ? samples - 1 : first - 1;
      if (!stuck(first) || stuck(before)) continue;
      // The run starts where v reaches 0 (the series' v rings into it).
      const State old_state = stateAt(before);
      const double sign = old_state == State::kSlipPositive ? 1.0 : -1.0;
      int zero = first;
      while (stuck(zero) && sign * velocity(zero) > 0.0 && zero != origin) zero = next(zero);
      const bool crossed = stuck(zero) && zero != origin;
      if (!crossed) zero = first;
      for (int k = first; k != zero; k = next(k)) setState(k, old_state);
      if (std::abs(hold(zero)) > limit_[l]) {
        // A reversal at v = 0; where the series' v slows down without
        // reaching 0, the slip goes on.
        const State through = crossed ? opposite(old_state) : old_state;
        for (int k = zero; stuck(k) && k != origin; k = next(k)) setState(k, through);
        continue;
      }
      const int start = zero;
      int k = next(start);
      for (; k != start; k = next(k)) {
        if (std::abs(hold(k)) > limit_[l]) break;
        setState(k, State::kStick);
      }
      // Slip against λ through the series' flicker, up to the first sample
      // that clearly slides either way (kSlidingFraction of max|v|): a stick
      // that ends slips against λ even where the series' v still rings about 0.
      const State slip = force(k) > 0.0 ? State::kSlipNegative : State::kSlipPositive;
      for (int j = k; j != start; j = next(j)) {
        if (std::abs(velocity(j)) > kSlidingFraction * sliding_scale) break;
        setState(j, slip);
      }
    }
  }
}

// The instants where a law's state changes between two samples of the
// span (its last sample wraps to the first, mirrored in half-period mode),
// placed by linear interpolation of the quantity that vanishes there. Rows
// of equal states are skipped a block at a time: switches are few.
void MonodromyStability::findSwitches() {
  const int samples = span_, laws = laws_;
  const double step = 2.0 * M_PI / model_.omega / model_.samples;
  switches_.clear();
  const State* states = states_.data();
  constexpr int kBlock = 32;
  for (int k = 0; k < samples; ++k) {
    if (k + kBlock < samples &&
        std::memcmp(states + static_cast<size_t>(k) * laws, states + static_cast<size_t>(k + 1) * laws,
                    sizeof(State) * kBlock * laws) == 0) {
      k += kBlock - 1;
      continue;
    }
    const bool wraps = k + 1 == samples;
    const int next = wraps ? 0 : k + 1;
    const double flip = wraps && half_period_ ? -1.0 : 1.0;  // the mirrored first sample
    const State *now = states + static_cast<size_t>(k) * laws, *then = states + static_cast<size_t>(next) * laws;
    for (int l = 0; l < laws; ++l) {
      const State a = now[l], b = flip < 0.0 ? mirror(then[l]) : then[l];
      if (a == b) continue;
      double fraction = 0.5;
      if (a == State::kOpen) fraction = switchCrossing(gap_[l] - u_(k, l), gap_[l] - u_(next, l));
      else if (a == State::kClosed) fraction = switchCrossing(r_(k, l), r_(next, l));
      else if (a == State::kStick)
        fraction = switchCrossing(std::abs(r_(k, l)) - limit_[l], std::abs(r_(next, l)) - limit_[l]);
      else fraction = switchCrossing(v_(k, l), flip * v_(next, l));
      switches_.push_back({(k + fraction) * step, l, a, b});
    }
  }
  std::stable_sort(switches_.begin(), switches_.end(), [](const Switch& x, const Switch& y) { return x.time < y.time; });
}

void MonodromyStability::mirrorStates(std::vector<State>& states) const {
  for (State& s : states) s = mirror(s);
}

const MonodromyStability::Phase& MonodromyStability::phase(const std::vector<State>& states) {
  phase_key_.assign(m_, false);
  for (size_t l = 0; l < states.size(); ++l) phase_key_[coords_[l]] = phase_key_[coords_[l]] || held(states[l]);
  auto found = phases_.find(phase_key_);
  if (found != phases_.end()) return found->second;
  std::vector<int> coords;
  for (int i = 0; i < m_; ++i)
    if (phase_key_[i]) coords.push_back(i);
  Phase p;
  p.projector = orbits::holdDofs(propagated_.mass_inverse, coords).projector;
  Eigen::MatrixXd generator = Eigen::MatrixXd::Zero(2 * m_, 2 * m_);
  generator.topRightCorner(m_, m_).setIdentity();
  // A held DOF's velocity perturbation is 0 through the phase (the reset
  // that starts it sets it so), so its ẋ = v row is left out: the generator
  // then has no Jordan block at 0 and is decomposed (phase_exponential.h).
  for (int i : coords) generator(i, m_ + i) = 0.0;
  generator.bottomLeftCorner(m_, m_) = -p.projector * propagated_.stiffness;
  generator.bottomRightCorner(m_, m_) = -p.projector * propagated_.damping;
  p.exponential = PhaseExponential(generator);
  return phases_.emplace(phase_key_, std::move(p)).first->second;
}

// [v; Q b] of the full forced system at (t, y) in `states`: b = f(t) − K x
// − C v + the slip forces; held DOFs take what their constraint needs.
void MonodromyStability::field(const std::vector<State>& states, double t, const Eigen::VectorXd& y,
                               Eigen::VectorXd& f) {
  const Phase& p = phase(states);
  force_.noalias() = -propagated_.stiffness * y.head(m_);
  force_.noalias() -= propagated_.damping * y.segment(m_, m_);
  for (const HarmonicLoad& load : model_.structure.loads)
    force_ += load_directions_.col(load.dof) * load.at(model_.omega * t);
  for (size_t l = 0; l < states.size(); ++l) addSlipForce(static_cast<int>(l), states[l], force_);
  f.resize(2 * m_);
  f.head(m_) = y.segment(m_, m_);
  for (int i = 0; i < m_; ++i)
    if (phase_key_[i]) f[i] = 0.0;
  f.tail(m_).noalias() = p.projector * force_;
}

// The orbit's [q; q̇] at time t from its propagated coefficients (O(m nb),
// the harmonics' cosines and sines by rotation from the first's: a switch
// costs no pass over the structure's DOFs nor a sincos per harmonic).
void MonodromyStability::orbitState(double t, Eigen::VectorXd& y) const {
  const int nb = model_.basis.size();
  const std::vector<int>& ks = model_.basis.harmonics();
  const Eigen::Map<const Eigen::MatrixXd> q(orbit_coefficients_, nb, m_);
  y.setZero(2 * m_);
  const double w = model_.omega, c1 = std::cos(w * t), s1 = std::sin(w * t);
  double c = 1.0, sn = 0.0;  // cos, sin of k ω t for k = 0, 1, 2, ... up to ks[h]
  int k = 0;
  for (size_t h = 0; h < ks.size(); ++h) {
    const int o = model_.basis.offset(static_cast<int>(h));
    for (; k < ks[h]; ++k) {
      const double next_c = c * c1 - sn * s1;
      sn = sn * c1 + c * s1;
      c = next_c;
    }
    if (ks[h] == 0) {
      y.head(m_) += q.row(o).transpose();
      continue;
    }
    const double kw = ks[h] * w;
    for (int j = 0; j < m_; ++j) {
      const double a = q(o, j), b = q(o + 1, j);
      y[j] += a * c + b * sn;
      y[m_ + j] += kw * (b * c - a * sn);
    }
  }
}

// Φ ← S Φ with S = R + (f⁺ − R f⁻) ∇gᵀ / ġ⁻ at switch s (header): R Φ
// plus a rank-one term, O(m²) rather than a product; S = I where the field
// is continuous (stick to slip, contact opening).
void MonodromyStability::applySaltation(const Switch& s, const std::vector<State>& before,
                                        const std::vector<State>& after, Eigen::MatrixXd& phi) {
  if (s.from == State::kStick || s.from == State::kClosed) return;
  const int i = coords_[s.law];
  orbitState(s.time, y_);
  const bool slipping = s.from != State::kOpen;
  if (slipping) y_[m_ + i] = 0.0;  // the event: the slip velocity vanishes
  const bool reset = held(s.to);   // R holds the DOF's velocity at 0
  const int gradient = slipping ? m_ + i : i;  // g = v_i, or the gap's x_i (sign cancels)
  field(before, s.time, y_, f_before_);
  if (reset) y_[m_ + i] = 0.0;
  field(after, s.time, y_, f_after_);
  const double rate = f_before_[gradient];
  gradient_row_ = phi.row(gradient);
  if (reset) {
    phi.row(m_ + i).setZero();
    f_before_[m_ + i] = 0.0;
  }
  if (!(std::abs(rate) > 0.0) || !std::isfinite(rate)) return;
  f_after_ -= f_before_;
  phi.noalias() += (f_after_ / rate) * gradient_row_;
}

// The orbit's coefficients on the propagation's coordinates: q = P x per
// coefficient when reduced (O(n nb m) once a point), else x itself.
void MonodromyStability::projectCoefficients(const Eigen::VectorXd& full) {
  if (projection_.size() == 0) {
    orbit_coefficients_ = full.data();
    return;
  }
  const int nb = model_.basis.size();
  const Eigen::Map<const Eigen::MatrixXd> x(full.data(), nb, n_);
  projected_.noalias() = x * projection_.transpose();
  orbit_coefficients_ = projected_.data();
}

HillResult MonodromyStability::analyse(double omega, const Eigen::VectorXd& full) {
  const auto start = std::chrono::steady_clock::now();
  if (!(omega > 0.0) || !std::isfinite(omega)) throwInputError("omega", formatNumber(omega), "must be finite and > 0");
  model_.checkSolutionSize(full);
  model_.omega = omega;
  ++point_;
  const double period = 2.0 * M_PI / omega;
  if (springs_) return verdict(springs_->multipliers(omega, full, work_.exponentials, work_.syntheses), period, start);
  // The caches by set of held DOFs start afresh once this large (between
  // points: no reference into them is held), bounding their memory.
  if (phases_.size() > kMaxCachedSets) phases_.clear();
  if (holdings_.size() > 16 * kMaxCachedSets) {
    holdings_.clear();
    last_holding_ = nullptr;
    last_key_.clear();
  }
  projectCoefficients(full);
  classify(full);
  keepHeldRuns(full);
  findSwitches();
  const double span = half_period_ ? 0.5 * period : period;
  if (switches_.empty()) {
    // One phase the whole period (stuck throughout, say): the multipliers
    // are exp(λ T) of its generator's eigenvalues, no product to form.
    current_.assign(states_.begin(), states_.begin() + laws_);
    const PhaseExponential& whole = phase(current_).exponential;
    if (whole.decomposed()) {
      ++work_.exponentials;
      multipliers_.resize(2 * m_);
      whole.multipliers(period, multipliers_);
      return verdict(multipliers_, period, start);
    }
  }
  if (!switches_.empty() && leading_modes_ && chainLeadingModes(span)) {
    work_.exponentials += static_cast<long>(switches_.size());
    return verdict(multipliers_, period, start);
  }
  propagateSpan(span);
  return multipliers(phi_, period, start);
}

// Φ over the span from just after the first switch round it back to that
// switch (in half-period mode the span's end is the first switch mirrored,
// where the states read at the span's start come back with their slip
// directions swapped: they are mirrored there so that the saltation is the
// first switch's own).
void MonodromyStability::propagateSpan(double span) {
  phi_.setIdentity(2 * m_, 2 * m_);
  current_.assign(states_.begin(), states_.begin() + laws_);
  if (switches_.empty()) {
    phase(current_).exponential.apply(span, phi_, scratch_);
    ++work_.exponentials;
    return;
  }
  current_[switches_[0].law] = switches_[0].to;
  for (size_t j = 0; j < switches_.size(); ++j) {
    const bool wraps = j + 1 == switches_.size();
    const Switch& s = switches_[wraps ? 0 : j + 1];
    const double previous = switches_[j].time;
    const double tau = wraps ? s.time + span - previous : s.time - previous;
    phase(current_).exponential.apply(tau, phi_, scratch_);
    ++work_.exponentials;
    if (wraps && half_period_) mirrorStates(current_);
    after_ = current_;
    after_[s.law] = s.to;
    applySaltation(s, current_, after_, phi_);
    current_.swap(after_);
  }
}

// Φ carried in each phase's leading modes (as SpringLawMonodromy's chain,
// spring_law_modes.cpp): after phase q the product is V_q a with a on the
// modes that outlast q (PhaseExponential::survivingModes); a switch's
// saltation acts on V_q a (d x columns, not d x d), and the next phase reads
// a = V_r⁻¹ x on its own leading modes. Started at the phase that keeps the
// fewest, p, the cyclic product's eigenvalues are those of the p-sized
// matrix (the rest are 0). On a large reduced structure most modes are the
// interface's stiff, heavily damped ones and a few are kept: the products
// are d x kept x kept where the full route's are d³ a phase. False (nothing
// done) where some phase's exponential is not decomposed.
bool MonodromyStability::chainLeadingModes(double span) {
  const size_t phases = switches_.size();
  phase_states_.resize(phases);
  phase_refs_.clear();
  phase_length_.resize(phases);
  kept_.resize(phases);
  current_.assign(states_.begin(), states_.begin() + laws_);
  current_[switches_[0].law] = switches_[0].to;
  size_t start = 0;
  for (size_t j = 0; j < phases; ++j) {
    const Switch& s = switches_[(j + 1) % phases];
    phase_length_[j] = j + 1 < phases ? s.time - switches_[j].time : s.time + span - switches_[j].time;
    phase_states_[j] = current_;
    const Phase& p = phase(current_);
    if (!p.exponential.decomposed()) return false;
    phase_refs_.push_back(&p);
    kept_[j] = p.exponential.survivingModes(phase_length_[j]);
    if (kept_[j] < kept_[start]) start = j;
    current_[s.law] = s.to;
  }
  const Eigen::Index columns = kept_[start];
  Eigen::Index rows = columns;
  modal_.setIdentity(rows, columns);
  for (size_t k = 0; k < phases; ++k) {
    const size_t q = (start + k) % phases, r = (q + 1) % phases;
    const PhaseExponential& from = phase_refs_[q]->exponential;
    if (k > 0) from.scaleModes(phase_length_[q], modal_);  // phase p's own scaling comes last
    physical_.noalias() = from.vectors().leftCols(rows) * modal_;
    // Half-period mode: the span's last phase meets the first switch mirrored (propagateSpan).
    const bool mirrored = half_period_ && r == 0;
    if (mirrored) {
      after_ = phase_states_[q];
      mirrorStates(after_);
    }
    applySaltation(switches_[r], mirrored ? after_ : phase_states_[q], phase_states_[r], physical_);
    rows = kept_[r];
    modal_.noalias() = phase_refs_[r]->exponential.inverse().topRows(rows) * physical_;
  }
  phase_refs_[start]->exponential.scaleModes(phase_length_[start], modal_);
  multipliers_.setZero(2 * m_);
  if (columns == 0) return true;
  eigen_.compute(modal_, false);
  if (eigen_.info() != Eigen::Success) {
    multipliers_.resize(0);  // verdict() reports the failure
    return true;
  }
  multipliers_.head(columns) = eigen_.eigenvalues();
  if (half_period_) multipliers_ = multipliers_.array().square().matrix();  // of Φ_h
  return true;
}

HillResult MonodromyStability::multipliers(const Eigen::MatrixXd& phi, double period,
                                           std::chrono::steady_clock::time_point start) {
  eigen_.compute(phi, false);
  if (eigen_.info() != Eigen::Success) return verdict(Eigen::VectorXcd(), period, start);
  multipliers_ = eigen_.eigenvalues();
  if (half_period_) multipliers_ = multipliers_.array().square().matrix();  // of Φ_h
  return verdict(multipliers_, period, start);
}

HillResult MonodromyStability::verdict(const Eigen::VectorXcd& multipliers, double period,
                                       std::chrono::steady_clock::time_point start) const {
  HillResult result;
  if (multipliers.size() == 0) {
    result.method = "monodromy";
    result.state_dimension = result.candidates = result.pencil_size = 2 * m_;
    result.failure = "the eigenvalues of the monodromy matrix did not converge";
  } else {
    result = stabilityFromMultipliers(multipliers, period, unit_tolerance_, "monodromy");
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace eqhb
