// The condensed harmonic-balance system on λ alone (hb_systems.h): x = B λ + c
// from A_k's factors at each ω, the law residuals and the chain rule through
// B for the Jacobian.
#include <algorithm>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/system_memory.h"
#include "eqhb/size_limits.h"

namespace eqhb {

namespace {
bool sparseCondensation(const HbModel& model, LinearAlgebra algebra) {
  if (algebra == LinearAlgebra::kAuto)
    return model.structure.dofs() >= kSparseCondensationFromDofs;
  return algebra == LinearAlgebra::kSparse;
}

// The condensed system fits on the chosen path: dense A_k factors count
// (w n)² each, sparse ones their entries.
void checkCondensedFits(const HbModel& model, LinearAlgebra algebra) {
  const bool sparse = sparseCondensation(model, algebra);
  checkBytes("harmonics", std::to_string(model.basis.count()),
             std::string("the condensed system with ") + (sparse ? "sparse" : "dense") + " factors of A_k " +
                 describeSizes(model),
             condensedBytes(model, sparse));
}
}  // namespace

CondensedSystem::CondensedSystem(HbModel model, LinearAlgebra algebra, const Deadline& deadline)
    : HbSystem(std::move(model), [algebra](const HbModel& m) { checkCondensedFits(m, algebra); }),
      factors_(model_.structure, model_.basis, sparseCondensation(model_, algebra), deadline) {
  components_ = model_.lawComponents();
  size_ = components_ * nb_;
  for (const auto& attached : model_.laws)
    for (int a = 0; a < attached.law->dimension(); ++a) {
      component_row_.push_back(attached.attachment.row(a));
      component_sign_.push_back(attached.law->forceSign());
    }
  coupling_.assign(components_,
                   std::vector<Eigen::MatrixXd>(components_, Eigen::MatrixXd::Zero(nb_, 2)));
  offset_.assign(components_, Eigen::VectorXd::Zero(nb_));
  condenseAt(model_.omega, deadline);
}

void CondensedSystem::setOmega(double omega) { condenseAt(omega, Deadline()); }

void CondensedSystem::condenseAt(double omega, const Deadline& deadline) {
  if (!(omega > 0.0) || !std::isfinite(omega))
    throwInputError("omega", formatNumber(omega), "must be finite and > 0");
  try {
    factors_.factorize(model_.structure, omega, deadline);
  } catch (const TimeLimitReached&) {
    throw;  // only in the constructor: there is no previous ω to return to
  } catch (...) {
    // Keep the system usable at the previous ω.
    if (factored_) factors_.factorize(model_.structure, model_.omega);
    throw;
  }
  factored_ = true;
  const bool moved = omega != model_.omega;  // at construction ρ is set for this ω already
  model_.omega = omega;
  if (moved) setScaleFreeRhos();
  const int n = model_.structure.dofs();
  const Eigen::VectorXd f = forcingCoefficients(model_);
  const auto& ks = model_.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    deadline.check("set-up of the condensed system: receptance at the laws, " + std::to_string(h) + " of " +
                   std::to_string(ks.size()) + " harmonics done");
    const int k = ks[h], w = harmonicWidth(k), o = model_.basis.offset(static_cast<int>(h));
    // W A_k⁻¹ [f_k | Wᵀ_k s]: the compliance W A⁻¹ Wᵀ seen by the laws.
    // A_k (k > 0) commutes with the quarter-period shift J (a, b) -> (-b, a),
    // and a component's sine load is J of its cosine load: its response is
    // J of the cosine response. The sparse factors are complex, where the
    // two are one solve anyway, so only the cosine loads are solved for
    // there; the dense path solves both (its results stay bit for bit).
    const bool shift = w == 2 && factors_.sparse();
    const int loads = shift ? 1 : w;  // load columns per component
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(w * n, 1 + components_ * loads);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) rhs(r * n + i, 0) = f[i * nb_ + o + r];
    for (int c = 0; c < components_; ++c)
      for (const AttachmentTerm& term : component_row_[c])
        for (int r = 0; r < loads; ++r) rhs(r * n + term.dof, 1 + c * loads + r) += component_sign_[c] * term.weight;
    const Eigen::MatrixXd map = factors_.solve(static_cast<int>(h), rhs);
    // Row r of the response to component c's load j (the shifted cosine one for a shifted sine load).
    auto response = [&](int r, int dof, int c, int j) {
      if (!shift || j == 0) return map(r * n + dof, 1 + c * loads + j);
      return r == 0 ? -map(n + dof, 1 + c) : map(dof, 1 + c);
    };
    for (int q = 0; q < components_; ++q) {
      const std::vector<AttachmentTerm>& terms = component_row_[q];
      for (int r = 0; r < w; ++r) {
        // u_q = Σ_j W_qj x_j, the first term assigned (a unit row copies x_j exactly).
        auto read = [&](auto&& column) {
          double u = terms.front().weight * column(terms.front().dof);
          for (size_t k = 1; k < terms.size(); ++k) u += terms[k].weight * column(terms[k].dof);
          return u;
        };
        offset_[q][o + r] = read([&](int dof) { return map(r * n + dof, 0); });
        for (int c = 0; c < components_; ++c)
          for (int j = 0; j < w; ++j) coupling_[q][c](o + r, j) = read([&](int dof) { return response(r, dof, c, j); });
      }
    }
  }
}

double CondensedSystem::responseAtLaws() const {
  double most = 0.0;
  const auto& ks = model_.basis.harmonics();
  for (const auto& c : offset_)
    for (size_t h = 0; h < ks.size(); ++h) {
      const int o = model_.basis.offset(static_cast<int>(h));
      most = std::max(most, ks[h] == 0 ? std::abs(c[o]) : std::hypot(c[o], c[o + 1]));
    }
  return most;
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
  const Eigen::VectorXd f = forcingCoefficients(model_);
  const auto& ks = model_.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int w = harmonicWidth(ks[h]), o = model_.basis.offset(static_cast<int>(h));
    // x_k = A_k⁻¹ (f_k + W_k λ_k) at every DOF.
    Eigen::MatrixXd rhs(w * n, 1);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) rhs(r * n + i, 0) = f[i * nb_ + o + r];
    for (int c = 0; c < components_; ++c)
      for (const AttachmentTerm& term : component_row_[c])
        for (int r = 0; r < w; ++r) rhs(r * n + term.dof, 0) += component_sign_[c] * term.weight * z[c * nb_ + o + r];
    const Eigen::MatrixXd x = factors_.solve(static_cast<int>(h), rhs);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) full[i * nb_ + o + r] = x(r * n + i, 0);
  }
  full.tail(components_ * nb_) = z;
  return full;
}

Eigen::VectorXd CondensedSystem::fromFullCoefficients(const Eigen::VectorXd& full) const {
  return full.tail(components_ * nb_);
}

}  // namespace eqhb
