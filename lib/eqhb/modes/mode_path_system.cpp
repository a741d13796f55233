#include "eqhb/modes/mode_path_system.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "eqhb/harmonic_balance/dense_from_pattern.h"
#include "eqhb/sparse_slots.h"

namespace eqhb {

PathWeights PathWeights::at(const ModeSystem& system, const Eigen::VectorXd& y, double omega_unit, double s_unit) {
  const int nx = system.motionCount(), inner = system.size(), nl = system.omegaIndex() - nx;
  const double shape = std::max(y.head(nx).norm(), 1e-300);
  const double forces = std::max(y.segment(nx, nl).norm(), 1e-300);
  PathWeights p;
  p.w = Eigen::VectorXd::Zero(inner + 1);
  p.w.head(nx).setConstant(1.0 / (0.01 * shape * shape));
  if (nl > 0 && nx > 0) p.w.segment(nx, nl).setConstant(1.0 / (0.01 * forces * forces));
  p.w[system.omegaIndex()] = 1.0 / (omega_unit * omega_unit);
  p.w[system.xiIndex()] = 1.0 / (omega_unit * omega_unit);
  p.w[inner] = 1.0 / (s_unit * s_unit);
  return p;
}

ModePathSystem::ModePathSystem(ModeSystem& mode, const Eigen::VectorXd& offset)
    : mode_(mode), inner_(mode.size()), size_(mode.size() + 1) {
  offset_ = offset.size() ? offset : Eigen::VectorXd::Zero(mode.omegaIndex());
  if (offset_.size() != mode.omegaIndex()) throw std::invalid_argument("ModePathSystem: one offset per coefficient");
  z_.setZero(inner_);
  amplitude_column_.setZero(inner_);
  constraint_.setZero(size_);
  mode_jacobian_ = mode_.jacobianPattern();
  buildPattern();
}

void ModePathSystem::buildPattern() {
  const SparseMatrix& inner = mode_.jacobianPattern();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(inner.nonZeros() + 2 * size_);
  for (int j = 0; j < inner.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(inner, j); it; ++it) entries.emplace_back(it.row(), j, 0.0);
  for (int r = 0; r < inner_; ++r) entries.emplace_back(r, inner_, 0.0);  // ∂g/∂s
  for (int c = 0; c < size_; ++c) entries.emplace_back(inner_, c, 0.0);   // the arclength row
  pattern_.resize(size_, size_);
  pattern_.setFromTriplets(entries.begin(), entries.end());
  pattern_.makeCompressed();
  mode_slot_.resize(inner.nonZeros());
  for (int j = 0; j < inner.outerSize(); ++j)
    for (int p = inner.outerIndexPtr()[j]; p < inner.outerIndexPtr()[j + 1]; ++p)
      mode_slot_[p] = slotOf(pattern_, inner.innerIndexPtr()[p], j);
  s_column_ = pattern_.outerIndexPtr()[inner_];
  row_slots_.resize(size_);
  for (int c = 0; c < size_; ++c) row_slots_[c] = slotOf(pattern_, inner_, c);
}

Eigen::VectorXd ModePathSystem::pathPoint(const Eigen::VectorXd& z, double amplitude) const {
  Eigen::VectorXd y(size_);
  const int coefficients = mode_.omegaIndex();
  y.head(coefficients) = (z.head(coefficients) - offset_) / amplitude;
  y.segment(coefficients, 2) = z.segment(coefficients, 2);
  y[inner_] = std::log(amplitude);
  return y;
}

Eigen::VectorXd ModePathSystem::modePoint(const Eigen::VectorXd& y) const {
  Eigen::VectorXd z(inner_);
  const int coefficients = mode_.omegaIndex();
  z.head(coefficients) = offset_ + y.head(coefficients) * std::exp(y[inner_]);
  z.tail(2) = y.segment(coefficients, 2);
  return z;
}

void ModePathSystem::setConstraint(const PathWeights& weights, const Eigen::VectorXd& tangent,
                                   const Eigen::VectorXd& predicted) {
  constraint_ = weights.w.cwiseProduct(tangent);
  constraint_at_prediction_ = constraint_.dot(predicted);
}

bool ModePathSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> g) {
  return evaluate(y, g, nullptr);
}

bool ModePathSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> g,
                                         Eigen::Ref<Eigen::MatrixXd> jacobian) {
  values_.resize(pattern_.nonZeros());
  const bool ok = evaluate(y, g, values_.data());
  denseFromPattern(pattern_, values_.data(), jacobian);
  return ok;
}

bool ModePathSystem::residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& y,
                                               Eigen::Ref<Eigen::VectorXd> g, SparseMatrix& jacobian) {
  if (jacobian.rows() != size_ || jacobian.cols() != size_ || jacobian.nonZeros() != pattern_.nonZeros() ||
      !jacobian.isCompressed())
    throw std::invalid_argument("residualAndSparseJacobian: the matrix lacks the Jacobian pattern");
  return evaluate(y, g, jacobian.valuePtr());
}

bool ModePathSystem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> g,
                              double* values) {
  const double s = y[inner_];
  if (!std::isfinite(s) || std::abs(s) > 700.0) return false;  // e^s stays a finite, nonzero amplitude
  const double a = std::exp(s);
  const int coefficients = mode_.omegaIndex();
  z_.head(coefficients) = offset_ + a * y.head(coefficients);
  z_.tail(2) = y.segment(coefficients, 2);
  mode_.setAmplitude(a);
  g[inner_] = constraint_.dot(y) - constraint_at_prediction_;  // ⟨τ, y − y_pred⟩ without a temporary
  if (!values) return mode_.residual(z_, g.head(inner_)) && std::isfinite(g[inner_]);
  if (!mode_.residualAndSparseJacobian(z_, g.head(inner_), mode_jacobian_)) return false;

  std::fill(values, values + pattern_.nonZeros(), 0.0);
  double* ds = values + s_column_;
  const double* mode_values = mode_jacobian_.valuePtr();
  for (int j = 0; j < mode_jacobian_.outerSize(); ++j) {
    const bool coefficient = j < coefficients;
    for (int p = mode_jacobian_.outerIndexPtr()[j]; p < mode_jacobian_.outerIndexPtr()[j + 1]; ++p) {
      if (!coefficient) {
        values[mode_slot_[p]] = mode_values[p];
        continue;
      }
      values[mode_slot_[p]] = a * mode_values[p];
      ds[mode_jacobian_.innerIndexPtr()[p]] += mode_values[p] * (z_[j] - offset_[j]);  // ∂g/∂z_q · (a q)
    }
  }
  mode_.amplitudeDerivative(amplitude_column_);  // ∂g/∂a, times ∂a/∂s = a
  for (int r = 0; r < inner_; ++r) ds[r] += a * amplitude_column_[r];
  for (int c = 0; c < size_; ++c) values[row_slots_[c]] = constraint_[c];
  return std::isfinite(g[inner_]);
}

void ModePathSystem::residualScales(Eigen::Ref<Eigen::VectorXd> scales) const {
  mode_.residualScales(scales.head(inner_));
  scales[inner_] = 1.0;
}

std::string ModePathSystem::violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& y) {
  mode_.setAmplitude(std::exp(y[inner_]));
  return mode_.violatedPhysics(modePoint(y));
}

}  // namespace eqhb
