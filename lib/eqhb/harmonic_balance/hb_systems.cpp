#include "eqhb/harmonic_balance/hb_systems.h"

#include <stdexcept>

#include "eqhb/error.h"

namespace eqhb {

namespace {
int harmonicWidth(int k) { return k == 0 ? 1 : 2; }
}  // namespace

Eigen::VectorXd forcingCoefficients(const HbModel& model) {
  const HarmonicSet& basis = model.basis;
  const int nb = basis.size();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model.structure.dofs() * nb);
  const auto& ks = basis.harmonics();
  for (const auto& load : model.structure.loads) {
    for (size_t h = 0; h < ks.size(); ++h) {
      if (ks[h] != load.harmonic) continue;
      const int o = load.dof * nb + basis.offset(static_cast<int>(h));
      f[o] += load.cos_amplitude;
      if (load.harmonic != 0) f[o + 1] += load.sin_amplitude;
    }
  }
  return f;
}

HbSystem::HbSystem(HbModel model)
    : model_((model.validate(), std::move(model))), laws_(model_), nb_(model_.basis.size()) {}

// ---------------------------------------------------------------- full system

FullSystem::FullSystem(HbModel model) : HbSystem(std::move(model)) {
  const int n = model_.structure.dofs();
  dynamic_rows_ = n * nb_;
  size_ = (n + model_.lawComponents()) * nb_;
  forcing_ = forcingCoefficients(model_);
  setOmega(model_.omega);
}

void FullSystem::setOmega(double omega) {
  if (!(omega > 0.0) || !std::isfinite(omega))
    throwInputError("omega", formatNumber(omega), "must be finite and > 0");
  model_.omega = omega;
  const int n = model_.structure.dofs();
  linear_operator_.setZero(dynamic_rows_, dynamic_rows_);
  const auto& ks = model_.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int k = ks[h], w = harmonicWidth(k), o = model_.basis.offset(static_cast<int>(h));
    const Eigen::MatrixXd a = model_.structure.harmonicOperator(k, omega);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int ri = 0; ri < w; ++ri)
          for (int cj = 0; cj < w; ++cj)
            linear_operator_(i * nb_ + o + ri, j * nb_ + o + cj) = a(ri * n + i, cj * n + j);
  }
}

bool FullSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                          Eigen::Ref<Eigen::VectorXd> g) {
  return evaluate(z, g, nullptr);
}

bool FullSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                     Eigen::Ref<Eigen::VectorXd> g,
                                     Eigen::Ref<Eigen::MatrixXd> jacobian) {
  return evaluate(z, g, &jacobian);
}

bool FullSystem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& z,
                          Eigen::Ref<Eigen::VectorXd> g, Eigen::Ref<Eigen::MatrixXd>* jacobian) {
  // Dynamics: A x − f − Σ sign_l λ_l on the law DOFs.
  g.head(dynamic_rows_).noalias() = linear_operator_ * z.head(dynamic_rows_);
  g.head(dynamic_rows_) -= forcing_;
  if (jacobian) {
    jacobian->setZero();
    jacobian->topLeftCorner(dynamic_rows_, dynamic_rows_) = linear_operator_;
  }
  for (int l = 0; l < laws_.lawCount(); ++l) {
    const AttachedLaw& attached = laws_.law(l);
    const int d = laws_.dimension(l);
    const double sign = attached.law->forceSign();
    for (int a = 0; a < d; ++a) {
      const int dof = attached.dofs[a];
      const int lambda = dynamic_rows_ + model_.componentIndex(l, a) * nb_;
      laws_.displacement(l).col(a) = z.segment(dof * nb_, nb_);
      laws_.force(l).col(a) = z.segment(lambda, nb_);
      g.segment(dof * nb_, nb_) -= sign * z.segment(lambda, nb_);
      if (jacobian)
        jacobian->block(dof * nb_, lambda, nb_, nb_).diagonal().array() -= sign;
    }
    if (!laws_.evaluate(l, model_.omega, jacobian != nullptr)) return false;
    for (int a = 0; a < d; ++a) {
      const int row = dynamic_rows_ + model_.componentIndex(l, a) * nb_;
      g.segment(row, nb_) = laws_.residual(l).col(a);
      if (!jacobian) continue;
      for (int b = 0; b < d; ++b) {
        const int dof = attached.dofs[b];
        const int lambda = dynamic_rows_ + model_.componentIndex(l, b) * nb_;
        jacobian->block(row, dof * nb_, nb_, nb_) += laws_.displacementBlock(l, a, b);
        jacobian->block(row, lambda, nb_, nb_) += laws_.forceBlock(l, a, b);
      }
    }
  }
  return g.allFinite();
}

// ----------------------------------------------------------- condensed system

CondensedSystem::CondensedSystem(HbModel model) : HbSystem(std::move(model)) {
  components_ = model_.lawComponents();
  size_ = components_ * nb_;
  for (const auto& attached : model_.laws)
    for (int dof : attached.dofs) component_dof_.push_back(dof);
  coupling_.assign(components_,
                   std::vector<Eigen::MatrixXd>(components_, Eigen::MatrixXd::Zero(nb_, 2)));
  offset_.assign(components_, Eigen::VectorXd::Zero(nb_));
  setOmega(model_.omega);
}

void CondensedSystem::setOmega(double omega) {
  if (!(omega > 0.0) || !std::isfinite(omega))
    throwInputError("omega", formatNumber(omega), "must be finite and > 0");
  const int n = model_.structure.dofs();
  const Eigen::VectorXd f = forcingCoefficients(model_);
  std::vector<double> component_sign;
  for (const auto& attached : model_.laws)
    for (int a = 0; a < attached.law->dimension(); ++a)
      component_sign.push_back(attached.law->forceSign());

  std::vector<Eigen::MatrixXd> maps;
  const auto& ks = model_.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int k = ks[h], w = harmonicWidth(k), o = model_.basis.offset(static_cast<int>(h));
    const int s = w * n;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(s, 1 + components_ * w);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) rhs(r * n + i, 0) = f[i * nb_ + o + r];
    for (int c = 0; c < components_; ++c)
      for (int r = 0; r < w; ++r) rhs(r * n + component_dof_[c], 1 + c * w + r) = component_sign[c];
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(model_.structure.harmonicOperator(k, omega));
    if (!(lu.rcond() > 1e-13))
      throw std::runtime_error("condensation impossible: the dynamic stiffness of harmonic " +
                               std::to_string(k) + " is singular at omega = " +
                               formatNumber(omega) + " (rcond " + formatNumber(lu.rcond()) +
                               "); use the full system");
    maps.push_back(lu.solve(rhs));
  }
  model_.omega = omega;
  harmonic_maps_ = std::move(maps);
  for (int q = 0; q < components_; ++q) {
    const int dof = component_dof_[q];
    for (size_t h = 0; h < ks.size(); ++h) {
      const int w = harmonicWidth(ks[h]), o = model_.basis.offset(static_cast<int>(h));
      const Eigen::MatrixXd& map = harmonic_maps_[h];
      for (int r = 0; r < w; ++r) {
        offset_[q][o + r] = map(r * n + dof, 0);
        for (int c = 0; c < components_; ++c)
          for (int j = 0; j < w; ++j) coupling_[q][c](o + r, j) = map(r * n + dof, 1 + c * w + j);
      }
    }
  }
}

bool CondensedSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                               Eigen::Ref<Eigen::VectorXd> g) {
  return evaluate(z, g, nullptr);
}

bool CondensedSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                          Eigen::Ref<Eigen::VectorXd> g,
                                          Eigen::Ref<Eigen::MatrixXd> jacobian) {
  return evaluate(z, g, &jacobian);
}

bool CondensedSystem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& z,
                               Eigen::Ref<Eigen::VectorXd> g,
                               Eigen::Ref<Eigen::MatrixXd>* jacobian) {
  const auto& ks = model_.basis.harmonics();
  const int harmonics = static_cast<int>(ks.size());
  if (jacobian) jacobian->setZero();
  for (int l = 0; l < laws_.lawCount(); ++l) {
    const int d = laws_.dimension(l);
    for (int a = 0; a < d; ++a) {
      const int q = model_.componentIndex(l, a);
      // x at this component's DOF = B λ + c, harmonic by harmonic.
      auto x = laws_.displacement(l).col(a);
      x = offset_[q];
      for (int c = 0; c < components_; ++c)
        for (int h = 0; h < harmonics; ++h) {
          const int w = harmonicWidth(ks[h]), o = model_.basis.offset(h);
          for (int r = 0; r < w; ++r)
            for (int j = 0; j < w; ++j) x[o + r] += coupling_[q][c](o + r, j) * z[c * nb_ + o + j];
        }
      laws_.force(l).col(a) = z.segment(q * nb_, nb_);
    }
    if (!laws_.evaluate(l, model_.omega, jacobian != nullptr)) return false;
    for (int a = 0; a < d; ++a) {
      const int row = model_.componentIndex(l, a) * nb_;
      g.segment(row, nb_) = laws_.residual(l).col(a);
      if (!jacobian) continue;
      auto rows = jacobian->middleRows(row, nb_);
      for (int b = 0; b < d; ++b) {
        const int qb = model_.componentIndex(l, b);
        rows.middleCols(qb * nb_, nb_) += laws_.forceBlock(l, a, b);
        // Chain rule through x = B λ + c: columns mix within each harmonic.
        const Eigen::MatrixXd& block = laws_.displacementBlock(l, a, b);
        for (int c = 0; c < components_; ++c)
          for (int h = 0; h < harmonics; ++h) {
            const int w = harmonicWidth(ks[h]), o = model_.basis.offset(h);
            for (int j = 0; j < w; ++j)
              for (int r = 0; r < w; ++r)
                rows.col(c * nb_ + o + j) += coupling_[qb][c](o + r, j) * block.col(o + r);
          }
      }
    }
  }
  return g.allFinite();
}

Eigen::VectorXd CondensedSystem::fullCoefficients(const Eigen::VectorXd& z) const {
  const int n = model_.structure.dofs();
  Eigen::VectorXd full = Eigen::VectorXd::Zero((n + components_) * nb_);
  const auto& ks = model_.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int w = harmonicWidth(ks[h]), o = model_.basis.offset(static_cast<int>(h));
    Eigen::VectorXd coeffs(1 + components_ * w);
    coeffs[0] = 1.0;
    for (int c = 0; c < components_; ++c)
      for (int j = 0; j < w; ++j) coeffs[1 + c * w + j] = z[c * nb_ + o + j];
    const Eigen::VectorXd x = harmonic_maps_[h] * coeffs;
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) full[i * nb_ + o + r] = x[r * n + i];
  }
  full.tail(components_ * nb_) = z;
  return full;
}

Eigen::VectorXd CondensedSystem::fromFullCoefficients(const Eigen::VectorXd& full) const {
  return full.tail(components_ * nb_);
}

std::unique_ptr<HbSystem> makeHbSystem(const HbModel& model, bool condensed) {
  if (condensed) return std::make_unique<CondensedSystem>(model);
  return std::make_unique<FullSystem>(model);
}

}  // namespace eqhb
