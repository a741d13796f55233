#include "eqhb/stability/spring_law_monodromy.h"

#include <algorithm>
#include <cmath>

#include "eqhb/harmonic_balance/fourier_transform.h"
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

}  // namespace

bool SpringLawMonodromy::supports(const HbModel& model) {
  if (model.laws.empty()) return false;
  for (const AttachedLaw& a : model.laws) {
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
  laws_ = static_cast<int>(model_.laws.size());
  transform_ = std::make_unique<FourierTransform>(model_.basis, model_.samples);
  const int samples = model_.samples, nb = model_.basis.size();
  for (const AttachedLaw& a : model_.laws) {
    std::unique_ptr<JenkinsAft> reader;
    if (const auto* c = dynamic_cast<const PenaltyContact*>(a.law.get())) {
      contact_.push_back(true);
      spring_.push_back(c->stiffness());
      limit_.push_back(0.0);
      gap_.push_back(c->gap());
    } else {
      contact_.push_back(false);
      const JenkinsAft* aft = oneSlider(*a.law);
      const Jenkins* exact = exactJenkins(*a.law);
      spring_.push_back(aft ? aft->sliders().front().k_t : exact->stiffness());
      limit_.push_back(aft ? aft->muN() : exact->muN());
      gap_.push_back(0.0);
      if (exact) reader = std::make_unique<JenkinsAft>(std::vector<JenkinsAft::Slider>{{exact->muN(), exact->stiffness()}});
    }
    LawSamples s;
    s.resize(samples, 1, reader ? reader->historyTerms() : a.law->historyTerms());
    samples_.push_back(std::move(s));
    readers_.push_back(std::move(reader));
  }
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

// u, u̇ and the force per sample, and the state per sample by the law's own
// rule (header).
void SpringLawMonodromy::classify(double omega, const Eigen::VectorXd& full, long& syntheses) {
  const int nb = model_.basis.size(), samples = model_.samples, n = model_.structure.dofs();
  active_.assign(static_cast<size_t>(samples) * laws_, 0);
  sliders_ = 0;
  for (int l = 0; l < laws_; ++l) {
    const AttachedLaw& a = model_.laws[l];
    a.attachment.gatherCoefficients(full.data(), nb, 0, buffer_.data());
    transform_->synthesize(buffer_.data(), u_.col(l).data());
    transform_->differentiate(buffer_.data(), omega, derivative_.data());
    transform_->synthesize(derivative_.data(), rate_.col(l).data());
    transform_->synthesize(full.data() + static_cast<std::ptrdiff_t>(n + model_.componentIndex(l, 0)) * nb,
                           force_.col(l).data());
    syntheses += 3;
    slot_[l] = -1;
    if (contact_[l]) {
      for (int k = 0; k < samples; ++k) active_[static_cast<size_t>(k) * laws_ + l] = u_(k, l) > gap_[l];
      continue;
    }
    // The slider's state from its return map over u, as the harmonic
    // balance evaluates it: stuck where ∂Ψ/∂u = k_t; its force F = λ − Ψ.
    // The exact law's orbit is read the same way, the map started where
    // its force is furthest from the limit, at the slider's position there,
    // w = u + λ/k_t: a slider that slips forgets it, one that never slips
    // keeps the force the harmonic balance gives it.
    LawSamples& s = samples_[l];
    s.displacement.col(0) = u_.col(l);
    s.force.col(0) = force_.col(l);
    if (readers_[l]) {
      Eigen::Index deepest = 0;
      force_.col(l).cwiseAbs().minCoeff(&deepest);
      const double anchor = u_(deepest, l) + force_(deepest, l) / spring_[l];
      readers_[l]->evaluateFrom(&anchor, s, true);
    } else {
      a.law->evaluate(s, true);
    }
    bool slips = false;
    for (int k = 0; k < samples; ++k) {
      const bool stuck = s.dpsi_ddisplacement(k, 0) > 0.0;
      active_[static_cast<size_t>(k) * laws_ + l] = stuck;
      slips = slips || !stuck;
      force_(k, l) -= s.psi(k, 0);
    }
    if (slips) slot_[l] = sliders_++;
  }
}

void SpringLawMonodromy::findSwitches(double omega) {
  const int samples = model_.samples;
  const double step = 2.0 * M_PI / omega / samples;
  switches_.clear();
  for (int k = 0; k < samples; ++k) {
    const int next = (k + 1) % samples;
    for (int l = 0; l < laws_; ++l) {
      const bool a = active_[static_cast<size_t>(k) * laws_ + l], b = active_[static_cast<size_t>(next) * laws_ + l];
      if (a == b) continue;
      double fraction = 0.5;
      if (contact_[l]) {
        fraction = switchCrossing(u_(k, l) - gap_[l], u_(next, l) - gap_[l]);
      } else if (a) {
        // Slip onset: the stuck force's trial value at the next sample
        // against the limit.
        const double limit = limit_[l];
        const double trial = force_(k, l) - spring_[l] * (u_(next, l) - u_(k, l));
        fraction = switchCrossing(std::abs(force_(k, l)) - limit, std::abs(trial) - limit);
      } else {
        fraction = switchCrossing(rate_(k, l), rate_(next, l));  // stick onset: u̇ = 0
      }
      switches_.push_back({(k + fraction) * step, l, b});
    }
  }
  std::stable_sort(switches_.begin(), switches_.end(), [](const Switch& x, const Switch& y) { return x.time < y.time; });
}

// A₁₁ of (1) (header): [0 ΩI; −M⁻¹K/Ω −M⁻¹C] with the stuck and closed
// springs in K. In [δq; δq̇/Ω] (a similarity: the multipliers are the same)
// the blocks are of one size, which the exponential's scaling and squaring
// needs: unscaled, the stiff contact springs on light interface DOFs
// (‖M⁻¹K‖ ~ 4e14 on the lap joint) made it overflow.
Eigen::MatrixXd SpringLawMonodromy::structuralGenerator(const std::vector<char>& active,
                                                        Eigen::MatrixXd& stiffness) const {
  stiffness = stiffness_;
  for (int l = 0; l < laws_; ++l)
    if (active[l]) stiffness.noalias() += spring_[l] * direction_[l] * direction_[l].transpose();
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
    if (active[l] && slot_[l] >= 0) a.block(m_, 2 * m_ + slot_[l], m_, 1) = spring_[l] / scale_ * (mass_inverse_ * direction_[l]);
  return generators_.emplace(std::move(key), PhaseExponential(a)).first->second;
}

double SpringLawMonodromy::phaseLength(size_t j, double period) const {
  const double end = switches_[(j + 1) % switches_.size()].time, begin = switches_[j].time;
  return j + 1 < switches_.size() ? end - begin : end + period - begin;
}

// (4): a stick onset sets the anchor's perturbation to wᵀδq.
bool SpringLawMonodromy::resetsAnchor(const Switch& s) const {
  return !contact_[s.law] && s.to_active && slot_[s.law] >= 0;
}

// Φ = Π R_j exp(A_j τ_j) from just after the first switch round the
// period, each phase's exponential applied to the whole Φ.
void SpringLawMonodromy::chainInFull(double period) {
  const int d = 2 * m_ + sliders_;
  phi_.setIdentity(d, d);
  for (size_t j = 0; j < switches_.size(); ++j) {
    const Switch& s = switches_[(j + 1) % switches_.size()];
    generator(phase_states_[j]).apply(phaseLength(j, period), phi_, scratch_);
    if (resetsAnchor(s)) phi_.row(2 * m_ + slot_[s.law]) = direction_[s.law].transpose() * phi_.topRows(m_);
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
  current_[switches_[0].law] = switches_[0].to_active;
  phase_states_.resize(switches_.size());
  phase_modes_.clear();
  bool usable = true;
  for (size_t j = 0; j < switches_.size(); ++j) {
    phase_states_[j] = current_;
    const ActiveModes& modes = activeModes(current_);
    phase_modes_.push_back(&modes);
    usable = usable && modes.usable;
    const Switch& s = switches_[(j + 1) % switches_.size()];
    current_[s.law] = s.to_active;
  }
  exponentials += static_cast<long>(switches_.size());
  if (usable) chainLeadingModes(period);
  else chainInFull(period);
  return multipliers_;
}

}  // namespace eqhb
