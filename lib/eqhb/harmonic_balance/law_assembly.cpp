#include "eqhb/harmonic_balance/law_assembly.h"

#include <algorithm>
#include <cmath>

namespace eqhb {

namespace {
// Half a period suffices when every law is odd (Law::oddSymmetric): on an odd
// basis Ψ is then antiperiodic and its partials half-period periodic.
Sampling lawSampling(const HbModel& model) {
  for (const AttachedLaw& a : model.laws)
    if (!a.law->oddSymmetric()) return Sampling::kFullPeriod;
  return Sampling::kHalfWave;
}
}  // namespace

LawAssembly::LawAssembly(const HbModel& model)
    : laws_(model.laws), transform_(model.basis, model.samples, lawSampling(model)) {
  const int nb = model.basis.size();
  const int n = transform_.activeSamples();
  slots_.resize(laws_.size());
  int most_channels = 0, history_terms = 0;
  for (size_t l = 0; l < laws_.size(); ++l) {
    const int d = laws_[l].law->dimension();
    Slot& s = slots_[l];
    s.displacement_coefficients.setZero(nb, d);
    s.force_coefficients.setZero(nb, d);
    s.psi_coefficients.setZero(nb, d);
    s.omega_coefficients.setZero(nb, d);
    s.derived_coefficients.setZero(nb, 2 * d);
    most_channels = std::max(most_channels, 4 * d);  // x, ẋ, λ, λ̇ per component
    s.samples.resize(n, d, laws_[l].law->historyTermsOn(n));
    history_terms = std::max(history_terms, laws_[l].law->historyTermsOn(n));
    s.displacement_blocks.assign(d * d, Eigen::MatrixXd::Zero(nb, nb));
    s.force_blocks.assign(d * d, Eigen::MatrixXd::Zero(nb, nb));
  }
  gram_scratch_.setZero(nb, nb);
  velocity_scratch_.setZero(nb, nb);
  sample_scratch_.setZero(n);
  channels_.resize(most_channels);
  if (history_terms > 0) {  // a history law is never odd: the full period is sampled
    synthesis_.setZero(n, nb);
    projection_.setZero(nb, n);
    // P by synthesising each basis function; Q = diag(w) Pᵀ, the trapezoidal
    // projection (w = 1/N for the constant, 2/N for the others).
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(nb);
    for (int c = 0; c < nb; ++c) {
      unit[c] = 1.0;
      transform_.synthesize(unit.data(), synthesis_.col(c).data());
      unit[c] = 0.0;
    }
    const auto& ks = model.basis.harmonics();
    for (size_t h = 0; h < ks.size(); ++h) {
      const int o = model.basis.offset(static_cast<int>(h));
      for (int r = 0; r < (ks[h] == 0 ? 1 : 2); ++r)
        projection_.row(o + r) = (ks[h] == 0 ? 1.0 : 2.0) / n * synthesis_.col(o + r).transpose();
    }
    basis_mean_ = synthesis_.colwise().mean();
    history_rows_.setZero(n, nb);
  }
}

void LawAssembly::addHistoryBlock(const LawSamples& samples, int first_term, int terms, Eigen::MatrixXd& block) {
  const Eigen::Index n = samples.psi.rows();
  history_rows_.setZero();
  for (int k = first_term; k < first_term + terms; ++k)
    for (Eigen::Index i = 0; i < n; ++i) {
      const double weight = samples.history_weight(i, k);
      if (weight == 0.0) continue;
      const int j = samples.history_sample(i, k);
      if (j == LawSamples::kPeriodMean)
        history_rows_.row(i) += weight * basis_mean_;
      else
        history_rows_.row(i) += weight * synthesis_.row(j);
    }
  // block += Q (H P), column by column over the rows that have terms.
  for (Eigen::Index c = 0; c < history_rows_.cols(); ++c)
    for (Eigen::Index i = 0; i < n; ++i) {
      const double g = history_rows_(i, c);
      if (g != 0.0) block.col(c) += g * projection_.col(i);
    }
}

void LawAssembly::replaceLaws(const std::vector<AttachedLaw>& laws) {
  for (size_t l = 0; l < laws_.size(); ++l) laws_[l].law = laws[l].law;
}

bool LawAssembly::evaluate(int l, double omega, bool with_jacobian) {
  Slot& s = slots_[l];
  const Law& law = *laws_[l].law;
  const int d = law.dimension();
  // The channels to synthesise, two at a time (one transform per pair with
  // half-wave sampling); the derivatives' coefficients have their own columns.
  auto& channels = channels_;  // sized at construction: no allocation here
  int count = 0;
  for (int a = 0; a < d; ++a) {
    if (law.usesDisplacement())
      channels[count++] = {s.displacement_coefficients.col(a).data(), s.samples.displacement.col(a).data()};
    if (law.usesVelocity()) {
      double* velocity = s.derived_coefficients.col(2 * a).data();
      transform_.differentiate(s.displacement_coefficients.col(a).data(), omega, velocity);
      channels[count++] = {velocity, s.samples.velocity.col(a).data()};
    }
    channels[count++] = {s.force_coefficients.col(a).data(), s.samples.force.col(a).data()};
    if (law.usesForceRate()) {
      double* force_rate = s.derived_coefficients.col(2 * a + 1).data();
      transform_.differentiate(s.force_coefficients.col(a).data(), omega, force_rate);
      channels[count++] = {force_rate, s.samples.force_rate.col(a).data()};
    }
  }
  for (int c = 0; c + 1 < count; c += 2)
    transform_.synthesizePair(channels[c].first, channels[c + 1].first, channels[c].second,
                              channels[c + 1].second);
  if (count % 2 == 1) transform_.synthesize(channels[count - 1].first, channels[count - 1].second);
  law.evaluate(s.samples, with_jacobian);
  // NaN and Inf propagate through a sum, which vectorises (allFinite's
  // early-exit loop does not and costs as much as the law on N samples).
  if (!std::isfinite(s.samples.psi.sum())) return false;
  for (int a = 0; a < d; ++a)
    transform_.project(s.samples.psi.col(a).data(), s.psi_coefficients.col(a).data());
  if (!with_jacobian) return true;

  for (int a = 0; a < d; ++a) {
    for (int b = 0; b < d; ++b) {
      const int ab = a * d + b;
      transform_.gram(s.samples.dpsi_dforce.col(ab).data(), s.force_blocks[ab]);
      if (law.usesForceRate()) {  // chained through Dω like the velocity
        transform_.gram(s.samples.dpsi_dforce_rate.col(ab).data(), gram_scratch_);
        transform_.rightMultiplyDerivative(gram_scratch_, omega, velocity_scratch_);
        s.force_blocks[ab] += velocity_scratch_;
      }
      Eigen::MatrixXd& block = s.displacement_blocks[ab];
      if (law.usesDisplacement())
        transform_.gram(s.samples.dpsi_ddisplacement.col(ab).data(), block);
      else
        block.setZero();
      const int terms = law.historyTermsOn(transform_.activeSamples());
      if (terms > 0) addHistoryBlock(s.samples, ab * terms, terms, block);
      if (law.usesVelocity()) {
        transform_.gram(s.samples.dpsi_dvelocity.col(ab).data(), gram_scratch_);
        transform_.rightMultiplyDerivative(gram_scratch_, omega, velocity_scratch_);
        block += velocity_scratch_;
      }
    }
  }
  return true;
}

const Eigen::MatrixXd& LawAssembly::omegaDerivative(int l, double omega) {
  Slot& s = slots_[l];
  const Law& law = *laws_[l].law;
  const int d = law.dimension();
  for (int a = 0; a < d; ++a) {
    sample_scratch_.setZero();
    for (int b = 0; b < d; ++b) {
      if (law.usesVelocity())
        sample_scratch_.array() += s.samples.dpsi_dvelocity.col(a * d + b).array() * s.samples.velocity.col(b).array();
      if (law.usesForceRate())
        sample_scratch_.array() +=
            s.samples.dpsi_dforce_rate.col(a * d + b).array() * s.samples.force_rate.col(b).array();
    }
    sample_scratch_ /= omega;
    transform_.project(sample_scratch_.data(), s.omega_coefficients.col(a).data());
  }
  return s.omega_coefficients;
}

}  // namespace eqhb
