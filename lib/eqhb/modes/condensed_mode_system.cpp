#include "eqhb/modes/condensed_mode_system.h"

#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/problem_scales.h"

namespace eqhb {

namespace {
// μ comes out of the bordered solve as a difference of forces of the size
// of K x (the modal balance near resonance is small beside them), so it is
// known to about eps κ K x only: its scale is never below this share of the
// full system's dynamics scale (over max |M φ|), which the solves reach
// (beam-damper: every point converged at shares 1e-2 to 1e-6, the same
// modes to 1e-9; with the law force level alone, none converged).
constexpr double kRoundingShare = 1e-4;
// A_k(ω, ξ) = K − k²ω² M + i kω (C − ξ M) into `a`.
void fillDynamicStiffness(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping, const Eigen::MatrixXd& stiffness,
                          int k, double omega, double xi, Eigen::MatrixXcd& a) {
  a.real() = stiffness - (k * k * omega * omega) * mass;
  a.imag() = (k * omega) * (damping - xi * mass);
}
}  // namespace

CondensedModeSystem::CondensedModeSystem(const HbModel& model, const Eigen::VectorXd& shape, bool keep_static_loads)
    : ModeSystem(shape), full_(model, shape, keep_static_loads), laws_(full_.model()) {
  const HbModel& m = full_.model();
  m_ = m.lawComponents();
  if (m_ == 0)
    throwInputError("system", "condensed",
                    "a nonlinear mode on the condensed system needs a law (its unknowns are the law forces); a "
                    "structure without laws has its linear modes: use the full system");
  n_ = m.structure.dofs();
  nb_ = m.basis.size();
  coefficients_ = m_ * nb_;
  size_ = coefficients_ + 2;
  const auto& ks = m.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    harmonic_.push_back(ks[h]);
    offset_.push_back(m.basis.offset(static_cast<int>(h)));
    if (ks[h] == 1) fundamental_ = offset_.back();
  }
  mass_ = Eigen::MatrixXd(m.structure.mass);
  damping_ = Eigen::MatrixXd(m.structure.damping);
  stiffness_ = Eigen::MatrixXd(m.structure.stiffness);
  attachLaws();
  condenseStaticHarmonic();
  sizeBuffers();
}

void CondensedModeSystem::attachLaws() {
  const HbModel& m = full_.model();
  reads_transpose_.setZero(n_, m_);
  loads_.setZero(n_, m_);
  for (int l = 0; l < static_cast<int>(m.laws.size()); ++l) {
    const int first = m.componentIndex(l, 0), d = m.laws[l].law->dimension();
    const Eigen::MatrixXd w = m.laws[l].attachment.transposeDense(n_);
    reads_transpose_.middleCols(first, d) = w.cast<Complex>();
    loads_.middleCols(first, d) = (m.laws[l].law->forceSign() * w).cast<Complex>();
  }
  reads_ = reads_transpose_.transpose();
  mode_at_laws_ = (reads_.real() * shape_).cwiseAbs().maxCoeff();
  mass_shape_ = mass_ * shape_;
  border_loads_.setZero(n_ + 1, m_ + 1);
  border_loads_.topLeftCorner(n_, m_) = loads_;
  border_loads_(n_, m_) = 1.0;
  border_reads_rhs_.setZero(n_ + 1, m_ + 1);
  border_reads_rhs_.topLeftCorner(n_, m_) = reads_transpose_;
  border_reads_rhs_(n_, m_) = 1.0;
  bordered_.setZero(n_ + 1, n_ + 1);
  bordered_.col(n_).head(n_) = mass_shape_.cast<Complex>();
  bordered_.row(n_).head(n_) = mass_shape_.transpose().cast<Complex>();
}

void CondensedModeSystem::condenseStaticHarmonic() {
  static_coupling_.setZero(m_, m_);
  static_offset_.setZero(m_);
  static_load_.setZero(n_);
  for (size_t h = 0; h < harmonic_.size(); ++h) {
    if (harmonic_[h] != 0) continue;
    static_lu_.compute(stiffness_);
    if (!static_lu_.isInvertible())
      throwInputError("structure.stiffness", "(matrix)",
                      "is singular: the condensed mode system solves the static harmonic K x0 = f0 + W^T lambda0; "
                      "a structure free to move as a rigid body needs the full system");
    const Eigen::VectorXd f = forcingCoefficients(full_.model());
    for (int i = 0; i < n_; ++i) static_load_[i] = f[i * nb_ + offset_[h]];
    const Eigen::MatrixXd reads = reads_.real();
    static_coupling_ = reads * static_lu_.solve(Eigen::MatrixXd(loads_.real()));
    static_offset_ = reads * static_lu_.solve(static_load_);
  }
}

void CondensedModeSystem::sizeBuffers() {
  coupling_.assign(harmonic_.size(), Eigen::MatrixXcd::Zero(m_, m_));
  coupling_omega_ = coupling_;
  coupling_xi_ = coupling_;
  border_reads_.setZero(m_);
  border_reads_omega_.setZero(m_);
  border_reads_xi_.setZero(m_);
  defect_row_.setZero(m_);
  defect_row_omega_.setZero(m_);
  defect_row_xi_.setZero(m_);
  a_.setZero(n_, n_);
  right_.setZero(n_, m_);
  left_.setZero(n_, m_);
  mass_right_.setZero(n_, m_);
  derivative_.setZero(n_, m_);
  border_right_.setZero(n_ + 1, m_ + 1);
  border_left_.setZero(n_ + 1, m_ + 1);
  border_mass_right_.setZero(n_, m_ + 1);
  border_derivative_.setZero(n_, m_ + 1);
  border_product_.setZero(m_ + 1, m_ + 1);
  lu_ = Eigen::PartialPivLU<Eigen::MatrixXcd>(n_);
  bordered_lu_ = Eigen::PartialPivLU<Eigen::MatrixXcd>(n_ + 1);
  displacements_.setZero(nb_, m_);
  displacements_omega_.setZero(nb_, m_);
  displacements_xi_.setZero(nb_, m_);
  displacements_amplitude_.setZero(nb_, m_);
  amplitude_column_.setZero(size_);
}

void CondensedModeSystem::prepareAt(double omega) {
  full_.prepareAt(omega);
  laws_.replaceLaws(full_.model().laws);
}

namespace {
bool regular(const Eigen::PartialPivLU<Eigen::MatrixXcd>& lu) {
  const double pivot = lu.matrixLU().diagonal().cwiseAbs().minCoeff();
  return pivot > 0.0 && std::isfinite(pivot);
}
}  // namespace

bool CondensedModeSystem::receptanceAt(double omega, double xi, bool derivatives) {
  if (omega == cached_omega_ && xi == cached_xi_ && (cached_derivatives_ || !derivatives)) return true;
  cached_omega_ = -1.0;  // unusable until every harmonic is done
  for (size_t h = 0; h < harmonic_.size(); ++h)
    if (harmonic_[h] != 0 && !factorHarmonic(h, omega, xi, derivatives)) return false;
  cached_omega_ = omega;
  cached_xi_ = xi;
  cached_derivatives_ = derivatives;
  return true;
}

bool CondensedModeSystem::factorHarmonic(size_t h, double omega, double xi, bool derivatives) {
  const int k = harmonic_[h];
  fillDynamicStiffness(mass_, damping_, stiffness_, k, omega, xi, a_);
  const Complex ik(0.0, k), ikw(0.0, -k * omega);  // ∂A/∂ω's damping factor; ∂A/∂ξ = −i kω M
  if (k != 1) {
    lu_.compute(a_);
    if (!regular(lu_)) return false;
    right_.noalias() = lu_.solve(loads_);  // A_k⁻¹ S Wᵀ
    coupling_[h].noalias() = reads_ * right_;
    if (!derivatives) return true;
    left_.noalias() = lu_.transpose().solve(reads_transpose_);  // (W A_k⁻¹)ᵀ
    mass_right_.noalias() = mass_ * right_;
    derivative_.noalias() = damping_ * right_;
    derivative_ = ik * (derivative_ - xi * mass_right_) + (-2.0 * k * k * omega) * mass_right_;
    coupling_omega_[h].noalias() = -left_.transpose() * derivative_;
    derivative_ = ikw * mass_right_;
    coupling_xi_[h].noalias() = -left_.transpose() * derivative_;
    return true;
  }
  bordered_.topLeftCorner(n_, n_) = a_;
  bordered_lu_.compute(bordered_);
  if (!regular(bordered_lu_)) return false;
  border_right_.noalias() = bordered_lu_.solve(border_loads_);  // [X per Λ, X per a; μ per Λ, μ per a]
  coupling_[h].noalias() = reads_ * border_right_.topLeftCorner(n_, m_);
  border_reads_.noalias() = reads_ * border_right_.col(m_).head(n_);
  defect_row_ = border_right_.row(n_).head(m_);
  defect_gain_ = border_right_(n_, m_);
  if (!derivatives) return true;
  border_left_.noalias() = bordered_lu_.transpose().solve(border_reads_rhs_);  // reads of U and μ, transposed
  const auto solved = border_right_.topRows(n_);
  const auto readers = border_left_.topRows(n_);
  // Rows of −(reads Ā⁻¹) ∂Ā (Ā⁻¹ loads): U₁'s m then μ; columns: Λ₁'s m then a.
  const auto split = [&](std::vector<Eigen::MatrixXcd>& coupling, Eigen::VectorXcd& reads,
                         Eigen::RowVectorXcd& defect, Complex& gain) {
    border_product_.noalias() = -readers.transpose() * border_derivative_;
    coupling[h] = border_product_.topLeftCorner(m_, m_);
    reads = border_product_.col(m_).head(m_);
    defect = border_product_.row(m_).head(m_);
    gain = border_product_(m_, m_);
  };
  border_mass_right_.noalias() = mass_ * solved;
  border_derivative_.noalias() = damping_ * solved;
  border_derivative_ = ik * (border_derivative_ - xi * border_mass_right_) + (-2.0 * k * k * omega) * border_mass_right_;
  split(coupling_omega_, border_reads_omega_, defect_row_omega_, defect_gain_omega_);
  border_derivative_ = ikw * border_mass_right_;
  split(coupling_xi_, border_reads_xi_, defect_row_xi_, defect_gain_xi_);
  return true;
}

void CondensedModeSystem::readDisplacements(const Eigen::Ref<const Eigen::VectorXd>& z, bool derivatives) {
  for (size_t h = 0; h < harmonic_.size(); ++h) {
    const int o = offset_[h];
    if (harmonic_[h] == 0) {
      for (int q = 0; q < m_; ++q) {
        double u = static_offset_[q];
        for (int c = 0; c < m_; ++c) u += static_coupling_(q, c) * z[c * nb_ + o];
        displacements_(o, q) = u;
        displacements_omega_(o, q) = displacements_xi_(o, q) = 0.0;
      }
      continue;
    }
    // U = B Λ (+ b₁ a on the fundamental), and (u_c, u_s) = (Re U, −Im U).
    const bool fundamental = harmonic_[h] == 1;
    for (int q = 0; q < m_; ++q) {
      Complex u(0.0), u_omega(0.0), u_xi(0.0);
      for (int c = 0; c < m_; ++c) {
        const Complex force(z[c * nb_ + o], -z[c * nb_ + o + 1]);
        u += coupling_[h](q, c) * force;
        if (!derivatives) continue;
        u_omega += coupling_omega_[h](q, c) * force;
        u_xi += coupling_xi_[h](q, c) * force;
      }
      if (fundamental) {
        u += amplitude_ * border_reads_[q];
        u_omega += amplitude_ * border_reads_omega_[q];
        u_xi += amplitude_ * border_reads_xi_[q];
        displacements_amplitude_(o, q) = border_reads_[q].real();
        displacements_amplitude_(o + 1, q) = -border_reads_[q].imag();
      }
      displacements_(o, q) = u.real();
      displacements_(o + 1, q) = -u.imag();
      displacements_omega_(o, q) = u_omega.real();
      displacements_omega_(o + 1, q) = -u_omega.imag();
      displacements_xi_(o, q) = u_xi.real();
      displacements_xi_(o + 1, q) = -u_xi.imag();
    }
  }
}

bool CondensedModeSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) {
  return evaluate(z, g, nullptr);
}

bool CondensedModeSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                              Eigen::Ref<Eigen::VectorXd> g, Eigen::Ref<Eigen::MatrixXd> jacobian) {
  return evaluate(z, g, &jacobian);
}

bool CondensedModeSystem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                                   Eigen::Ref<Eigen::MatrixXd>* jacobian) {
  const double omega = z[coefficients_], xi = z[coefficients_ + 1];
  if (!(omega > 0.0) || !std::isfinite(omega) || !std::isfinite(xi)) return false;
  if (!receptanceAt(omega, xi, jacobian != nullptr)) return false;
  readDisplacements(z, jacobian != nullptr);
  if (jacobian) {
    jacobian->setZero();
    amplitude_column_.setZero();
  }
  const HbModel& m = full_.model();
  for (int l = 0; l < laws_.lawCount(); ++l) {
    for (int a = 0; a < laws_.dimension(l); ++a) {
      const int q = m.componentIndex(l, a);
      laws_.displacement(l).col(a) = displacements_.col(q);
      laws_.force(l).col(a) = z.segment(q * nb_, nb_);
    }
    if (!laws_.evaluate(l, omega, jacobian != nullptr)) return false;
    for (int a = 0; a < laws_.dimension(l); ++a)
      g.segment(m.componentIndex(l, a) * nb_, nb_) = laws_.residual(l).col(a);
    if (jacobian) lawJacobian(l, omega, *jacobian);
  }
  borderRows(z, g, jacobian);
  return g.allFinite();
}

void CondensedModeSystem::lawJacobian(int l, double omega, Eigen::Ref<Eigen::MatrixXd> jacobian) {
  const HbModel& m = full_.model();
  const Eigen::MatrixXd& omega_derivative = laws_.omegaDerivative(l, omega);
  const int d = laws_.dimension(l);
  for (int a = 0; a < d; ++a) {
    const int first_row = m.componentIndex(l, a) * nb_;
    auto rows = jacobian.middleRows(first_row, nb_);
    rows.col(coefficients_) += omega_derivative.col(a);
    for (int b = 0; b < d; ++b) {
      const int qb = m.componentIndex(l, b);
      rows.middleCols(qb * nb_, nb_) += laws_.forceBlock(l, a, b);
      // The chain rule through U = B Λ + b₁ a (+ the static offset), B and
      // b₁ moving with ω and ξ.
      const Eigen::MatrixXd& block = laws_.displacementBlock(l, a, b);
      rows.col(coefficients_).noalias() += block * displacements_omega_.col(qb);
      rows.col(coefficients_ + 1).noalias() += block * displacements_xi_.col(qb);
      amplitude_column_.segment(first_row, nb_).noalias() += block * displacements_amplitude_.col(qb);
      for (size_t h = 0; h < harmonic_.size(); ++h) {
        const int o = offset_[h];
        if (harmonic_[h] == 0) {
          for (int c = 0; c < m_; ++c) rows.col(c * nb_ + o) += static_coupling_(qb, c) * block.col(o);
          continue;
        }
        for (int c = 0; c < m_; ++c) {
          const Complex b_qc = coupling_[h](qb, c);
          rows.col(c * nb_ + o) += b_qc.real() * block.col(o) - b_qc.imag() * block.col(o + 1);
          rows.col(c * nb_ + o + 1) += b_qc.imag() * block.col(o) + b_qc.real() * block.col(o + 1);
        }
      }
    }
  }
}

void CondensedModeSystem::borderRows(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                                     Eigen::Ref<Eigen::MatrixXd>* jacobian) {
  // μ = m₁ Λ₁ + h₁ a, Λ₁ = λ_c − i λ_s: Re μ and Im μ.
  const int o = fundamental_, re = coefficients_, im = coefficients_ + 1;
  // row Λ₁ + gain a: μ itself, or its derivative with the derivatives' row and gain.
  const auto applied = [&](const Eigen::RowVectorXcd& row, Complex gain) {
    Complex sum = gain * amplitude_;
    for (int c = 0; c < m_; ++c) sum += row[c] * Complex(z[c * nb_ + o], -z[c * nb_ + o + 1]);
    return sum;
  };
  const Complex mu = applied(defect_row_, defect_gain_);
  g[re] = mu.real();
  g[im] = mu.imag();
  if (!jacobian) return;
  const Complex mu_omega = applied(defect_row_omega_, defect_gain_omega_);
  const Complex mu_xi = applied(defect_row_xi_, defect_gain_xi_);
  Eigen::Ref<Eigen::MatrixXd>& j = *jacobian;
  for (int c = 0; c < m_; ++c) {
    const Complex r = defect_row_[c];  // ∂μ/∂λ_c = r, ∂μ/∂λ_s = −i r
    j(re, c * nb_ + o) = r.real();
    j(re, c * nb_ + o + 1) = r.imag();
    j(im, c * nb_ + o) = r.imag();
    j(im, c * nb_ + o + 1) = -r.real();
  }
  j(re, coefficients_) = mu_omega.real();
  j(im, coefficients_) = mu_omega.imag();
  j(re, coefficients_ + 1) = mu_xi.real();
  j(im, coefficients_ + 1) = mu_xi.imag();
  amplitude_column_[re] = defect_gain_.real();
  amplitude_column_[im] = defect_gain_.imag();
}

Eigen::VectorXd CondensedModeSystem::fullCoefficients(const Eigen::VectorXd& z) const {
  const double omega = z[coefficients_], xi = z[coefficients_ + 1];
  Eigen::VectorXd full = Eigen::VectorXd::Zero((n_ + m_) * nb_);
  Eigen::MatrixXcd a(n_, n_);
  for (size_t h = 0; h < harmonic_.size(); ++h) {
    const int k = harmonic_[h], o = offset_[h];
    Eigen::VectorXcd forces(m_);
    for (int c = 0; c < m_; ++c) forces[c] = Complex(z[c * nb_ + o], k == 0 ? 0.0 : -z[c * nb_ + o + 1]);
    if (k == 0) {
      const Eigen::VectorXd x = static_lu_.solve(static_load_ + loads_.real() * forces.real());
      for (int i = 0; i < n_; ++i) full[i * nb_ + o] = x[i];
      continue;
    }
    fillDynamicStiffness(mass_, damping_, stiffness_, k, omega, xi, a);
    Eigen::VectorXcd x;
    if (k == 1) {  // bordered, as the fundamental is solved (the header)
      Eigen::MatrixXcd bordered = bordered_;
      bordered.topLeftCorner(n_, n_) = a;
      Eigen::VectorXcd rhs(n_ + 1);
      rhs << loads_ * forces, Complex(amplitude_);
      x = bordered.partialPivLu().solve(rhs).head(n_);
    } else {
      x = a.partialPivLu().solve(loads_ * forces);
    }
    for (int i = 0; i < n_; ++i) {
      full[i * nb_ + o] = x[i].real();
      full[i * nb_ + o + 1] = -x[i].imag();
    }
  }
  full.tail(coefficients_) = z.head(coefficients_);
  return full;
}

void CondensedModeSystem::residualScales(Eigen::Ref<Eigen::VectorXd> scales) const {
  full_.setAmplitude(amplitude_);
  Eigen::VectorXd all(full_.size());
  full_.residualScales(all);  // [dynamics; laws; amplitude; phase]
  scales.head(coefficients_) = all.segment(n_ * nb_, coefficients_);
  // μ balances, along the mode, what the laws' forces give it (φᵀ S Wᵀ λ)
  // against the structure's small modal dynamic stiffness near resonance:
  // its scale is the law force level times the mode's reading at the laws,
  // not the structure's stiffness times the motion (10⁸ times larger on
  // beam-damper, where a 13 % change of amplitude then passed unnoticed).
  const PhysicalScales physical = physicalScales(full_.model(), amplitude_ * shape_.cwiseAbs().maxCoeff());
  const double modal_force = physical.force * mode_at_laws_;
  const double rounding = kRoundingShare * all[0] / mass_shape_.cwiseAbs().maxCoeff();
  scales.tail(2).setConstant(std::max(modal_force, rounding));
}

std::string CondensedModeSystem::violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) {
  Eigen::VectorXd point(full_.size());
  point << fullCoefficients(z), z[coefficients_], z[coefficients_ + 1];
  full_.setAmplitude(amplitude_);
  return full_.violatedPhysics(point);
}

}  // namespace eqhb
