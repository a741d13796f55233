#include "eqhb/modes/full_mode_system.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

#include "eqhb/error.h"
#include "eqhb/sparse_slots.h"
#include "eqhb/harmonic_balance/dense_from_pattern.h"
#include "eqhb/harmonic_balance/problem_scales.h"

namespace eqhb {

namespace {
HbModel unforced(HbModel model, bool keep_static_loads) {
  auto& loads = model.structure.loads;
  loads.erase(std::remove_if(loads.begin(), loads.end(),
                             [&](const HarmonicLoad& load) { return !(keep_static_loads && load.harmonic == 0); }),
              loads.end());
  return model;
}

}  // namespace

FullModeSystem::FullModeSystem(const HbModel& model, const Eigen::VectorXd& shape, bool keep_static_loads)
    : ModeSystem(shape), inner_(unforced(model, keep_static_loads)) {
  inner_.scaleRhoByStaticCompliance();  // ω is the mode's resonance: its dynamic compliance is 0 or ∞
  const HbModel& m = inner_.model();
  if (!m.basis.contains(1))
    throwInputError("harmonic_balance.harmonics", std::to_string(m.basis.count()),
                    "a nonlinear mode needs the fundamental (harmonic 1) in the basis");
  n_ = m.structure.dofs();
  if (shape.size() != n_) throw std::invalid_argument("FullModeSystem: the mode shape needs one value per DOF");
  nb_ = m.basis.size();
  dynamic_rows_ = n_ * nb_;
  inner_size_ = inner_.size();
  size_ = inner_size_ + 2;
  mass_ = m.structure.mass;
  damping_ = m.structure.damping;
  mass_shape_ = mass_ * shape_;
  harmonic_of_offset_.assign(nb_, 0);
  const auto& ks = m.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int o = m.basis.offset(static_cast<int>(h));
    harmonic_of_offset_[o] = ks[h];
    if (ks[h] != 0) harmonic_of_offset_[o + 1] = ks[h];
    if (ks[h] == 1) fundamental_ = o;
  }
  mass_x_.setZero(nb_, n_);
  damping_x_.setZero(nb_, n_);
  omega_derivative_.setZero(inner_size_);
  inner_jacobian_ = inner_.jacobianPattern();
  buildPattern();
  values_.setZero(pattern_.nonZeros());
  inner_.holdRho(true);
}

void FullModeSystem::buildPattern() {
  const SparseMatrix& inner = inner_.jacobianPattern();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(inner.nonZeros() + 2 * inner_size_ + 2 * n_);
  for (int j = 0; j < inner.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(inner, j); it; ++it) entries.emplace_back(it.row(), j, 0.0);
  for (int r = 0; r < inner_size_; ++r) entries.emplace_back(r, inner_size_, 0.0);  // ∂g/∂ω
  for (int r = 0; r < dynamic_rows_; ++r) entries.emplace_back(r, inner_size_ + 1, 0.0);  // ∂g/∂ξ
  for (int j = 0; j < n_; ++j) {
    entries.emplace_back(inner_size_, j * nb_ + fundamental_, 0.0);
    entries.emplace_back(inner_size_ + 1, j * nb_ + fundamental_ + 1, 0.0);
  }
  pattern_.resize(size_, size_);
  pattern_.setFromTriplets(entries.begin(), entries.end());
  pattern_.makeCompressed();

  inner_slot_.resize(inner.nonZeros());
  for (int j = 0; j < inner.outerSize(); ++j)
    for (int p = inner.outerIndexPtr()[j]; p < inner.outerIndexPtr()[j + 1]; ++p)
      inner_slot_[p] = slotOf(pattern_, inner.innerIndexPtr()[p], j);
  omega_column_ = pattern_.outerIndexPtr()[inner_size_];
  xi_column_ = pattern_.outerIndexPtr()[inner_size_ + 1];
  // −ξ k ω M on the (cos row, sin column) block, +ξ k ω M on (sin, cos):
  // inside the dynamics blocks of the inner pattern.
  for (int j = 0; j < mass_.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(mass_, j); it; ++it)
      for (int o = 0; o < nb_; ++o) {
        const int k = harmonic_of_offset_[o];
        if (k == 0 || (o > 0 && harmonic_of_offset_[o - 1] == k)) continue;  // cos offsets of k > 0
        xi_slot_.push_back(slotOf(pattern_, static_cast<int>(it.row()) * nb_ + o, j * nb_ + o + 1));
        xi_factor_.push_back(-k * it.value());
        xi_slot_.push_back(slotOf(pattern_, static_cast<int>(it.row()) * nb_ + o + 1, j * nb_ + o));
        xi_factor_.push_back(k * it.value());
      }
  amplitude_slot_.resize(n_);
  phase_slot_.resize(n_);
  for (int j = 0; j < n_; ++j) {
    amplitude_slot_[j] = slotOf(pattern_, inner_size_, j * nb_ + fundamental_);
    phase_slot_[j] = slotOf(pattern_, inner_size_ + 1, j * nb_ + fundamental_ + 1);
  }
}

void FullModeSystem::prepareAt(double omega) {
  inner_.holdRho(false);
  inner_.setOmega(omega);
  inner_.holdRho(true);
}

bool FullModeSystem::moveTo(double omega) {
  if (omega == inner_.omega()) return true;
  if (!(omega > 0.0) || !std::isfinite(omega)) return false;
  try {
    inner_.setOmega(omega);
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

bool FullModeSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) {
  return evaluate(z, g, nullptr);
}

bool FullModeSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                                     Eigen::Ref<Eigen::MatrixXd> jacobian) {
  const bool ok = evaluate(z, g, values_.data());
  denseFromPattern(pattern_, values_.data(), jacobian);  // small systems: the sparse values, dense
  return ok;
}

bool FullModeSystem::residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                           Eigen::Ref<Eigen::VectorXd> g, SparseMatrix& jacobian) {
  if (jacobian.rows() != size_ || jacobian.cols() != size_ || jacobian.nonZeros() != pattern_.nonZeros() ||
      !jacobian.isCompressed())
    throw std::invalid_argument("residualAndSparseJacobian: the matrix lacks the Jacobian pattern");
  return evaluate(z, g, jacobian.valuePtr());
}

bool FullModeSystem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                          double* values) {
  const double omega = z[inner_size_], xi = z[inner_size_ + 1];
  if (!std::isfinite(xi) || !moveTo(omega)) return false;
  bool ok = values ? inner_.residualAndSparseJacobian(z.head(inner_size_), g.head(inner_size_), inner_jacobian_)
                   : inner_.residual(z.head(inner_size_), g.head(inner_size_));
  if (!ok) return false;
  // Rows t of M X and C X, X = the displacement coefficients (nb x n).
  const Eigen::Map<const Eigen::MatrixXd> x(z.data(), nb_, n_);
  mass_x_.noalias() = x * mass_;
  Eigen::Map<Eigen::MatrixXd> dynamics(g.data(), nb_, n_);
  // −ξ M ẋ's share of A_k: −ξkω M x_s on the cos rows, +ξkω M x_c on the sin rows.
  for (int o = 0; o < nb_; ++o) {
    const int k = harmonic_of_offset_[o];
    if (k == 0 || (o > 0 && harmonic_of_offset_[o - 1] == k)) continue;
    dynamics.row(o) -= xi * k * omega * mass_x_.row(o + 1);
    dynamics.row(o + 1) += xi * k * omega * mass_x_.row(o);
  }
  g[inner_size_] = mass_x_.row(fundamental_).dot(shape_) - amplitude_;
  g[inner_size_ + 1] = mass_x_.row(fundamental_ + 1).dot(shape_);
  if (!values) return g.allFinite();

  std::fill(values, values + pattern_.nonZeros(), 0.0);
  const double* inner_values = inner_jacobian_.valuePtr();
  for (size_t p = 0; p < inner_slot_.size(); ++p) values[inner_slot_[p]] += inner_values[p];
  for (size_t e = 0; e < xi_slot_.size(); ++e) values[xi_slot_[e]] += xi * omega * xi_factor_[e];
  // ω and ξ columns: the dynamics rows from ∂A_k/∂ω and ∂A_k/∂ξ, the law rows
  // from the laws' own ω derivative.
  damping_x_.noalias() = x * damping_;
  inner_.lawOmegaDerivative(omega_derivative_);
  Eigen::Map<Eigen::MatrixXd> d_omega(omega_derivative_.data(), nb_, n_);
  double* xi_values = values + xi_column_;
  for (int o = 0; o < nb_; ++o) {
    const int k = harmonic_of_offset_[o];
    if (k == 0) {
      d_omega.row(o).setZero();
      for (int i = 0; i < n_; ++i) xi_values[i * nb_ + o] = 0.0;
      continue;
    }
    if (o > 0 && harmonic_of_offset_[o - 1] == k) continue;
    for (int i = 0; i < n_; ++i) {
      const double mc = mass_x_(o, i), ms = mass_x_(o + 1, i), cc = damping_x_(o, i), cs = damping_x_(o + 1, i);
      d_omega(o, i) = -2.0 * k * k * omega * mc + k * cs - xi * k * ms;
      d_omega(o + 1, i) = -2.0 * k * k * omega * ms - k * cc + xi * k * mc;
      xi_values[i * nb_ + o] = -k * omega * ms;
      xi_values[i * nb_ + o + 1] = k * omega * mc;
    }
  }
  std::copy(omega_derivative_.data(), omega_derivative_.data() + inner_size_, values + omega_column_);
  for (int j = 0; j < n_; ++j) {
    values[amplitude_slot_[j]] = mass_shape_[j];
    values[phase_slot_[j]] = mass_shape_[j];
  }
  return g.allFinite();
}

void FullModeSystem::residualScales(Eigen::Ref<Eigen::VectorXd> scales) const {
  const HbModel& m = inner_.model();
  const double displacement = amplitude_ * shape_.cwiseAbs().maxCoeff();
  const PhysicalScales physical = physicalScales(m, displacement);
  double stiffness = 0.0;
  for (int i = 0; i < n_; ++i)
    stiffness = std::max({stiffness, std::abs(m.structure.stiffness.coeff(i, i)),
                          m.omega * m.omega * std::abs(mass_.coeff(i, i))});
  scales.head(dynamic_rows_).setConstant(std::max(physical.force, stiffness * displacement));
  for (int l = 0; l < static_cast<int>(m.laws.size()); ++l)
    for (int a = 0; a < m.laws[l].law->dimension(); ++a)
      scales.segment(dynamic_rows_ + m.componentIndex(l, a) * nb_, nb_)
          .setConstant(m.laws[l].law->residualScale(physical, a));
  scales.tail(2).setConstant(amplitude_);
}

std::string FullModeSystem::violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) {
  if (!moveTo(z[inner_size_])) return "";
  return inner_.violatedPhysics(z.head(inner_size_));
}

}  // namespace eqhb
