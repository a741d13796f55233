#include "eqhb/stability/spring_law_monodromy.h"

#include <algorithm>
#include <cmath>

#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/laws/joints/elastic_friction_aft.h"
#include "eqhb/laws/joints/jenkins.h"
#include "eqhb/laws/joints/jenkins_aft.h"
#include "eqhb/laws/penalty_contact.h"
#include "eqhb/stability/switch_crossing.h"

namespace eqhb {

namespace {

const JenkinsAft* oneSlider(const Law& law) {
  const auto* j = dynamic_cast<const JenkinsAft*>(&law);
  return j && j->sliders().size() == 1 ? j : nullptr;
}

// The exact (equality-form) Jenkins element on one coordinate.
const Jenkins* exactJenkins(const Law& law) {
  const auto* j = dynamic_cast<const Jenkins*>(&law);
  return j && j->dimension() == 1 ? j : nullptr;
}

// The elastic-friction element with one tangent ([u_n; u_t]).
const ElasticFrictionAft* oneTangent(const Law& law) {
  const auto* e = dynamic_cast<const ElasticFrictionAft*>(&law);
  return e && !e->onPlane() && e->parameters().tangents == 1 ? e : nullptr;
}

}  // namespace

bool SpringLawMonodromy::supports(const HbModel& model) {
  if (model.laws.empty()) return false;
  for (const AttachedLaw& a : model.laws) {
    if (oneTangent(*a.law)) continue;
    if (a.law->dimension() != 1) return false;
    if (!oneSlider(*a.law) && !exactJenkins(*a.law) && !dynamic_cast<const PenaltyContact*>(a.law.get()))
      return false;
  }
  return true;
}

SpringLawMonodromy::SpringLawMonodromy(const HbModel& model, const Eigen::MatrixXd& mass_inverse,
                                       const Eigen::MatrixXd& damping, const Eigen::MatrixXd& stiffness,
                                       const std::vector<Eigen::VectorXd>& law_directions)
    : model_(model), mass_inverse_(mass_inverse), damping_(damping), stiffness_(stiffness), direction_(law_directions) {
  m_ = static_cast<int>(mass_inverse.rows());
  transform_ = std::make_unique<FourierTransform>(model_.basis, model_.samples);
  const int samples = model_.samples, nb = model_.basis.size();
  // One channel per law, two per elastic-friction element (header).
  auto addChannel = [&](bool contact, double spring, double limit, double gap, int partner) {
    contact_.push_back(contact);
    spring_.push_back(spring);
    limit_.push_back(limit);
    gap_.push_back(gap);
    partner_.push_back(partner);
  };
  for (const AttachedLaw& a : model_.laws) {
    first_channel_.push_back(static_cast<int>(contact_.size()));
    std::unique_ptr<JenkinsAft> reader;
    if (const auto* c = dynamic_cast<const PenaltyContact*>(a.law.get())) {
      addChannel(true, c->stiffness(), 0.0, c->gap(), -1);
    } else if (const ElasticFrictionAft* e = oneTangent(*a.law)) {
      const ElasticFrictionParameters& p = e->parameters();
      const int normal = static_cast<int>(contact_.size());
      addChannel(true, p.k_n, 0.0, p.gap, -1);
      addChannel(false, p.k_t, p.mu, 0.0, normal);
    } else {
      const JenkinsAft* aft = oneSlider(*a.law);
      const Jenkins* exact = exactJenkins(*a.law);
      addChannel(false, aft ? aft->sliders().front().k_t : exact->stiffness(), aft ? aft->muN() : exact->muN(), 0.0,
                 -1);
      if (exact) reader = std::make_unique<JenkinsAft>(std::vector<JenkinsAft::Slider>{{exact->muN(), exact->stiffness()}});
    }
    LawSamples s;  // read by a Jenkins slider's return map only
    if (!contact_.back() && partner_.back() < 0) s.resize(samples, 1, reader ? reader->historyTerms() : a.law->historyTerms());
    samples_.push_back(std::move(s));
    readers_.push_back(std::move(reader));
  }
  laws_ = static_cast<int>(contact_.size());
  if (static_cast<int>(direction_.size()) != laws_)
    throw std::logic_error("SpringLawMonodromy: one direction per law component expected");
  // Ω: the fastest rate with every spring in (the norm of M⁻¹K).
  Eigen::MatrixXd k = stiffness_;
  for (int l = 0; l < laws_; ++l) k.noalias() += spring_[l] * direction_[l] * direction_[l].transpose();
  scale_ = std::sqrt(std::max((mass_inverse_ * k).lpNorm<Eigen::Infinity>(), 1e-300));
  u_.resize(samples, laws_);
  rate_.resize(samples, laws_);
  force_.resize(samples, laws_);
  buffer_.resize(nb);
  derivative_.resize(nb);
  slot_.assign(laws_, -1);
}

SpringLawMonodromy::~SpringLawMonodromy() = default;

// u, u̇ (and a slider's force) per sample, and the state per sample by the
// law's own rule (header).
void SpringLawMonodromy::classify(double omega, const Eigen::VectorXd& full, long& syntheses) {
  const int nb = model_.basis.size(), samples = model_.samples, n = model_.structure.dofs();
  active_.assign(static_cast<size_t>(samples) * laws_, kFree);
  sliders_ = 0;
  slot_.assign(laws_, -1);
  for (size_t i = 0; i < model_.laws.size(); ++i) {
    const AttachedLaw& a = model_.laws[i];
    const int first = first_channel_[i], dimension = a.law->dimension();
    for (int c = 0; c < dimension; ++c) {
      a.attachment.gatherCoefficients(full.data(), nb, c, buffer_.data());
      transform_->synthesize(buffer_.data(), u_.col(first + c).data());
      transform_->differentiate(buffer_.data(), omega, derivative_.data());
      transform_->synthesize(derivative_.data(), rate_.col(first + c).data());
      syntheses += 2;
    }
    if (partner_[first + dimension - 1] >= 0) {
      classifyElasticSlider(*a.law, first);
      continue;
    }
    const int l = first;
    if (contact_[l]) {
      for (int k = 0; k < samples; ++k) state(k, l) = u_(k, l) > gap_[l] ? kHeld : kFree;
      continue;
    }
    const std::ptrdiff_t force_row = n + model_.componentIndex(static_cast<int>(i), 0);
    transform_->synthesize(full.data() + force_row * nb, force_.col(l).data());
    ++syntheses;
    // The slider's state from its return map over u, as the harmonic
    // balance evaluates it: stuck where ∂Ψ/∂u = k_t; its force F = λ − Ψ.
    // The exact law's orbit is read the same way, the map started where
    // its force is furthest from the limit, at the slider's position there,
    // w = u + λ/k_t: a slider that slips forgets it, one that never slips
    // keeps the force the harmonic balance gives it.
    LawSamples& s = samples_[i];
    s.displacement.col(0) = u_.col(l);
    s.force.col(0) = force_.col(l);
    if (readers_[i]) {
      Eigen::Index deepest = 0;
      force_.col(l).cwiseAbs().minCoeff(&deepest);
      const double anchor = u_(deepest, l) + force_(deepest, l) / spring_[l];
      readers_[i]->evaluateFrom(&anchor, s, true);
    } else {
      a.law->evaluate(s, true);
    }
    bool slips = false;
    for (int k = 0; k < samples; ++k) {
      const bool stuck = s.dpsi_ddisplacement(k, 0) > 0.0;
      state(k, l) = stuck ? kHeld : kFree;
      slips = slips || !stuck;
      force_(k, l) -= s.psi(k, 0);
    }
    if (slips) slot_[l] = sliders_++;
  }
}

// An elastic-friction element's states (header): its contact closed where
// u_n > g0, its slider by the law's return map over the samples (stick
// while |k_t (u_t − w)| <= μp, else slip and w follows), run twice from the
// law's start (ū_t or its static anchor), which makes it periodic. One
// change: where the contact closes between two samples the slider starts
// from u_t at the closing instant, not at the last open sample. Started
// there the map slips at the first closed sample whenever the tangential
// motion over the open part of the step exceeds μp/k_t, which the exact
// flow does not when k_t |u̇_t| < μ k_n u̇_n (it closes into stick); the
// anchor's reset, (4'') or (4'), then differs by O(1) and so did the
// radius (1.08 against 0.88 at isolated points of a smooth curve).
void SpringLawMonodromy::classifyElasticSlider(const Law& law, int normal) {
  const auto& e = static_cast<const ElasticFrictionAft&>(law);
  const int slider = normal + 1, samples = model_.samples;
  const double k_t = spring_[slider], k_n = spring_[normal], mu = limit_[slider], g0 = gap_[normal];
  double w = e.anchor().empty() ? u_.col(slider).mean() : e.anchor().front();
  bool sticks = false, slips = false;
  for (int pass = 0; pass < 2; ++pass)
    for (int k = 0; k < samples; ++k) {
      const int previous = (k + samples - 1) % samples;
      const double penetration = u_(k, normal) - g0, before = u_(previous, normal) - g0;
      force_(k, normal) = k_n * std::max(penetration, 0.0);
      state(k, normal) = penetration > 0.0 ? kHeld : kFree;
      if (!(penetration > 0.0)) {  // open: released, w follows u_t
        w = u_(k, slider);
        force_(k, slider) = 0.0;
        state(k, slider) = kFree;
        continue;
      }
      if (!(before > 0.0))
        w = u_(previous, slider) + switchCrossing(before, penetration) * (u_(k, slider) - u_(previous, slider));
      const double trial = k_t * (u_(k, slider) - w), limit = mu * force_(k, normal);
      if (std::abs(trial) <= limit) {
        force_(k, slider) = trial;
        state(k, slider) = kHeld;
      } else {
        force_(k, slider) = trial > 0.0 ? limit : -limit;
        w = u_(k, slider) - force_(k, slider) / k_t;
        state(k, slider) = trial > 0.0 ? kSlipPositive : kSlipNegative;
      }
      if (pass == 1) {
        sticks = sticks || state(k, slider) == kHeld;
        slips = slips || state(k, slider) != kHeld;
      }
    }
  if (sticks && slips) slot_[slider] = sliders_++;
}

void SpringLawMonodromy::findSwitches(double omega) {
  const int samples = model_.samples;
  const double step = 2.0 * M_PI / omega / samples;
  switches_.clear();
  for (int k = 0; k < samples; ++k) {
    const int next = (k + 1) % samples;
    for (int l = 0; l < laws_; ++l) {
      const char a = state(k, l), b = state(next, l);
      if (a == b) continue;
      if (partner_[l] >= 0) {
        switches_.push_back(elasticSliderSwitch(l, k, next, a, b, step));
        continue;
      }
      double fraction = 0.5;
      if (contact_[l]) {
        fraction = switchCrossing(u_(k, l) - gap_[l], u_(next, l) - gap_[l]);
      } else if (a == kHeld) {
        // Slip onset: the stuck force's trial value at the next sample
        // against the limit.
        const double limit = limit_[l];
        const double trial = force_(k, l) - spring_[l] * (u_(next, l) - u_(k, l));
        fraction = switchCrossing(std::abs(force_(k, l)) - limit, std::abs(trial) - limit);
      } else {
        fraction = switchCrossing(rate_(k, l), rate_(next, l));  // stick onset: u̇ = 0
      }
      switches_.push_back({(k + fraction) * step, l, b, 0.0});
    }
  }
  std::stable_sort(switches_.begin(), switches_.end(), [](const Switch& x, const Switch& y) { return x.time < y.time; });
}

SpringLawMonodromy::Switch SpringLawMonodromy::elasticSliderSwitch(int l, int k, int next, char a, char b,
                                                                    double step) const {
  const int normal = partner_[l];
  const double k_t = spring_[l], mu_k_n = limit_[l] * spring_[normal];
  Switch out{0.0, l, b, 0.0};
  double fraction = 0.5;
  if (a == kFree || b == kFree) {
    // The contact opens or closes: the normal channel's instant.
    fraction = switchCrossing(u_(k, normal) - gap_[normal], u_(next, normal) - gap_[normal]);
    if (b == kHeld) {
      // (4''): the anchor is u_t at the closing instant.
      const double rate_t = rate_(k, l) + fraction * (rate_(next, l) - rate_(k, l));
      const double rate_n = rate_(k, normal) + fraction * (rate_(next, normal) - rate_(k, normal));
      const double weight = -rate_t / rate_n;
      out.normal_reset = std::isfinite(weight) ? weight : 0.0;
    }
  } else if (a == kHeld) {
    // Slip onset: the stuck force's trial value at the next sample against
    // the limit there.
    const double trial = force_(k, l) + k_t * (u_(next, l) - u_(k, l));
    fraction = switchCrossing(std::abs(force_(k, l)) - limit_[l] * force_(k, normal),
                              std::abs(trial) - limit_[l] * force_(next, normal));
  } else {
    // From slip with T = s μ p: the slider's rate ẇ = u̇_t − s μ k_n u̇_n / k_t
    // vanishes (a stick onset, or a reversal shorter than a sample).
    const double sign = a == kSlipPositive ? 1.0 : -1.0;
    auto slide = [&](int j) { return rate_(j, l) - sign * mu_k_n * rate_(j, normal) / k_t; };
    fraction = switchCrossing(slide(k), slide(next));
    if (b == kHeld) out.normal_reset = -sign * mu_k_n / k_t;  // (4')
  }
  out.time = (k + fraction) * step;
  return out;
}

// A₁₁ of (1) (header): [0 ΩI; −M⁻¹K/Ω −M⁻¹C] with the stuck and closed
// springs in K. In [δq; δq̇/Ω] (a similarity: the multipliers are the same)
// the blocks are of one size, which the exponential's scaling and squaring
// needs: unscaled, the stiff contact springs on light interface DOFs
// (‖M⁻¹K‖ ~ 4e14 on the lap joint) made it overflow.
Eigen::MatrixXd SpringLawMonodromy::structuralGenerator(const std::vector<char>& active,
                                                        Eigen::MatrixXd& stiffness) const {
  stiffness = stiffness_;
  for (int l = 0; l < laws_; ++l) {
    if (active[l] == kHeld) stiffness.noalias() += spring_[l] * direction_[l] * direction_[l].transpose();
    if (active[l] == kSlipPositive || active[l] == kSlipNegative) {
      // T = s μ k_n (u_n − g0): the slider's force follows the normal coordinate.
      const double sign = active[l] == kSlipPositive ? 1.0 : -1.0;
      const int normal = partner_[l];
      stiffness.noalias() += sign * limit_[l] * spring_[normal] * direction_[l] * direction_[normal].transpose();
    }
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * m_, 2 * m_);
  a.block(0, m_, m_, m_).diagonal().setConstant(scale_);
  a.block(m_, 0, m_, m_) = -mass_inverse_ * stiffness / scale_;
  a.block(m_, m_, m_, m_) = -mass_inverse_ * damping_;
  return a;
}

// A of (1) (header) for the laws' states `active` and the current slots:
// A₁₁ and the stuck anchors' columns k_t M⁻¹ w (scaled by 1/Ω like K).
const PhaseExponential& SpringLawMonodromy::generator(const std::vector<char>& active) {
  auto key = std::make_pair(active, slot_);
  auto found = generators_.find(key);
  if (found != generators_.end()) return found->second;
  const int d = 2 * m_ + sliders_;
  Eigen::MatrixXd k;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(d, d);
  a.topLeftCorner(2 * m_, 2 * m_) = structuralGenerator(active, k);
  for (int l = 0; l < laws_; ++l)
    if (active[l] == kHeld && slot_[l] >= 0) a.block(m_, 2 * m_ + slot_[l], m_, 1) = spring_[l] / scale_ * (mass_inverse_ * direction_[l]);
  return generators_.emplace(std::move(key), PhaseExponential(a)).first->second;
}

double SpringLawMonodromy::phaseLength(size_t j, double period) const {
  const double end = switches_[(j + 1) % switches_.size()].time, begin = switches_[j].time;
  return j + 1 < switches_.size() ? end - begin : end + period - begin;
}

// (4), (4'), (4''): a stick onset sets the anchor's perturbation.
bool SpringLawMonodromy::resetsAnchor(const Switch& s) const {
  return !contact_[s.law] && s.state == kHeld && slot_[s.law] >= 0;
}

// Φ = Π R_j exp(A_j τ_j) from just after the first switch round the
// period, each phase's exponential applied to the whole Φ.
void SpringLawMonodromy::chainInFull(double period) {
  const int d = 2 * m_ + sliders_;
  phi_.setIdentity(d, d);
  for (size_t j = 0; j < switches_.size(); ++j) {
    const Switch& s = switches_[(j + 1) % switches_.size()];
    generator(phase_states_[j]).apply(phaseLength(j, period), phi_, scratch_);
    if (resetsAnchor(s)) resetAnchor(s, phi_, phi_.row(2 * m_ + slot_[s.law]));
  }
  eigenvaluesOf(phi_, d);
}

// multipliers_: the eigenvalues of phi, then 0 up to `size`.
void SpringLawMonodromy::eigenvaluesOf(const Eigen::Ref<const Eigen::MatrixXd>& phi, Eigen::Index size) {
  multipliers_.setZero(size);
  if (phi.rows() == 0) return;
  eigen_.compute(phi, false);
  if (eigen_.info() != Eigen::Success) {
    multipliers_.resize(0);  // the caller reports the failure
    return;
  }
  multipliers_.head(phi.rows()) = eigen_.eigenvalues();
}

const Eigen::VectorXcd& SpringLawMonodromy::multipliers(double omega, const Eigen::VectorXd& full,
                                                        long& exponentials, long& syntheses) {
  const double period = 2.0 * M_PI / omega;
  // A long curve keeps meeting new sets of states: the caches start afresh
  // (between points, no pointer into them held) once they hold this many,
  // which bounds their memory (~0.3 MB a set on the lap joint).
  if (modes_.size() > kMaxCachedSets) modes_.clear();
  if (generators_.size() > kMaxCachedSets) generators_.clear();
  classify(omega, full, syntheses);
  findSwitches(omega);
  const int d = 2 * m_ + sliders_;
  current_.assign(active_.begin(), active_.begin() + laws_);
  if (switches_.empty()) {
    // One phase the whole period: exp(A T)'s eigenvalues are e^{λT} of A₁₁'s
    // and 1 for each slider that slips throughout (its δz does not move).
    ++exponentials;
    const ActiveModes& modes = activeModes(current_);
    if (!modes.usable) {
      eigenvaluesOf(generator(current_).exponential(period), d);
      return multipliers_;
    }
    multipliers_.setOnes(d);
    modes.exponential.multipliers(period, multipliers_.head(2 * m_));
    return multipliers_;
  }
  // From just after the first switch round the period back to it: the
  // laws' states in each phase, which decide the route.
  current_[switches_[0].law] = switches_[0].state;
  phase_states_.resize(switches_.size());
  phase_modes_.clear();
  bool usable = true;
  for (size_t j = 0; j < switches_.size(); ++j) {
    phase_states_[j] = current_;
    const ActiveModes& modes = activeModes(current_);
    phase_modes_.push_back(&modes);
    usable = usable && modes.usable;
    const Switch& s = switches_[(j + 1) % switches_.size()];
    current_[s.law] = s.state;
  }
  exponentials += static_cast<long>(switches_.size());
  if (usable) chainLeadingModes(period);
  else chainInFull(period);
  return multipliers_;
}

}  // namespace eqhb
