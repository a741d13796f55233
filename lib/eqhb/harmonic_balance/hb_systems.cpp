#include "eqhb/harmonic_balance/hb_systems.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "eqhb/error.h"
#include "eqhb/sparse_slots.h"
#include "eqhb/harmonic_balance/dense_from_pattern.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/harmonic_balance/system_memory.h"
#include "eqhb/laws/dissipation_deficit.h"
#include "eqhb/size_limits.h"

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

HbSystem::HbSystem(HbModel model, const std::function<void(const HbModel&)>& fits)
    : model_((model.validate(), fits(model), withScaleFreeRhos(std::move(model)))), laws_(model_), nb_(model_.basis.size()) {}

void HbSystem::residualScales(Eigen::Ref<Eigen::VectorXd> scales) const {
  const PhysicalScales physical = physicalScales(model_, responseAtLaws());
  const int law_rows = model_.lawComponents() * nb_, first_law_row = size() - law_rows;
  scales.head(first_law_row).setConstant(physical.force);  // full system: A x − f − W λ
  for (int l = 0; l < static_cast<int>(model_.laws.size()); ++l)
    for (int a = 0; a < model_.laws[l].law->dimension(); ++a)
      scales.segment(first_law_row + model_.componentIndex(l, a) * nb_, nb_)
          .setConstant(model_.laws[l].law->residualScale(physical, a));
}

double HbSystem::unknownScale() const {
  const PhysicalScales physical = physicalScales(model_, responseAtLaws());
  return condensed() ? physical.force : std::hypot(physical.displacement, physical.force);
}

std::string HbSystem::violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) {
  Eigen::VectorXd g(size());
  if (!residual(z, g)) return "";  // not finite: the solver's verdict already refused it
  const PhysicalScales physical = physicalScales(model_, responseAtLaws());
  for (int l = 0; l < laws_.lawCount(); ++l)
    for (const auto& [name, value] : laws_.violations(l, physical))
      if (name == "dissipation_deficit" && !(value < kGrossDissipationDeficit)) {
        // A regularised form's width far off the contact's slip velocities is the usual cause.
        const std::string width = widthScaleAdvice(model_, l);
        return "law[" + std::to_string(l) + "] (" + model_.laws[l].law->type() + ") dissipates too little: " +
               name + " = " + formatNumber(value) + " (0 when the friction force opposes the slip at its limit)" +
               (width.empty() ? "" : "; " + width);
      }
  return "";
}

void HbSystem::setScaleFreeRhos() {
  if (rho_held_) return;
  // Each returns the model as it was when no ρ is scale-free.
  model_ = rho_static_ ? withStaticScaleFreeRhos(std::move(model_)) : withScaleFreeRhos(std::move(model_));
  laws_.replaceLaws(model_.laws);
}

void HbSystem::scaleRhoByStaticCompliance() {
  rho_static_ = true;
  setScaleFreeRhos();
}

// ---------------------------------------------------------------- full system

double FullSystem::responseAtLaws() const {
  if (response_omega_ != model_.omega) {
    try {
      response_ = linearResponseAtLaws(model_, model_.structure.dofs() >= kSparseCondensationFromDofs);
    } catch (const std::exception&) {
      response_ = 0.0;  // singular at this ω: the scales fall back on the loads and stiffness
    }
    response_omega_ = model_.omega;
  }
  return response_;
}

namespace {

// Values of m at the entries of pattern p (zeros where m has none).
Eigen::VectorXd valuesOnPattern(const SparseMatrix& m, const SparseMatrix& p) {
  Eigen::VectorXd values = Eigen::VectorXd::Zero(p.nonZeros());
  for (int j = 0; j < m.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(m, j); it; ++it) values[slotOf(p, it.row(), j)] += it.value();
  return values;
}
}  // namespace

FullSystem::FullSystem(HbModel model, const Deadline& deadline)
    : HbSystem(std::move(model), [](const HbModel& m) {
        checkBytes("harmonics", std::to_string(m.basis.count()), "the full system " + describeSizes(m), fullBytes(m));
      }) {
  const int n = model_.structure.dofs();
  dynamic_rows_ = n * nb_;
  size_ = (n + model_.lawComponents()) * nb_;
  forcing_ = forcingCoefficients(model_);
  buildPattern(deadline);
  setOmega(model_.omega);
}

void FullSystem::buildPattern(const Deadline& deadline) {
  const std::string step = "set-up of the full system: ";
  const int harmonics = static_cast<int>(model_.basis.harmonics().size()), laws = laws_.lawCount();
  auto harmonic = [&](int h) { return std::to_string(h) + " of " + std::to_string(harmonics) + " harmonics"; };
  auto law = [&](int l) { return std::to_string(l) + " of " + std::to_string(laws) + " laws"; };
  const LinearStructure& structure = model_.structure;
  SparseMatrix p = structure.pattern();
  p.makeCompressed();
  pattern_mass_ = valuesOnPattern(structure.mass, p);
  pattern_damping_ = valuesOnPattern(structure.damping, p);
  pattern_stiffness_ = valuesOnPattern(structure.stiffness, p);

  // Entries of A in the loop order of setOmega: harmonic, entry of P, block.
  using Entry = Eigen::Triplet<double>;
  std::vector<Entry> dynamics;
  const auto& ks = model_.basis.harmonics();
  // Reserved: regrowing a vector of tens of millions of entries takes
  // seconds, between two checks of the time limit.
  std::size_t dynamic_entries = 0;
  for (int k : ks) dynamic_entries += static_cast<std::size_t>(harmonicWidth(k) * harmonicWidth(k)) * p.nonZeros();
  dynamics.reserve(dynamic_entries);
  for (size_t h = 0; h < ks.size(); ++h) {
    deadline.check(step + "dynamics pattern, " + harmonic(static_cast<int>(h)) + " done");
    const int w = harmonicWidth(ks[h]), o = model_.basis.offset(static_cast<int>(h));
    for (int j = 0; j < p.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(p, j); it; ++it)
        for (int ri = 0; ri < w; ++ri)
          for (int cj = 0; cj < w; ++cj)
            dynamics.emplace_back(static_cast<int>(it.row()) * nb_ + o + ri, j * nb_ + o + cj, 0.0);
  }
  deadline.check(step + "sorting the dynamics pattern");
  linear_operator_.resize(dynamic_rows_, dynamic_rows_);
  linear_operator_.setFromTriplets(dynamics.begin(), dynamics.end());
  linear_operator_.makeCompressed();

  std::vector<Entry> all;
  std::size_t law_entries = 0;
  for (int l = 0; l < laws_.lawCount(); ++l)
    law_entries += static_cast<std::size_t>(laws_.dimension(l)) *
                   (laws_.law(l).attachment.dofs().size() * (nb_ + nb_ * nb_) + laws_.dimension(l) * nb_ * nb_);
  all.reserve(dynamics.size() + law_entries);
  all.insert(all.end(), dynamics.begin(), dynamics.end());
  for (int l = 0; l < laws_.lawCount(); ++l) {
    deadline.check(step + "law pattern, " + law(l) + " done");
    const AttachedLaw& attached = laws_.law(l);
    const int d = laws_.dimension(l);
    for (int a = 0; a < d; ++a) {
      const int lambda = dynamic_rows_ + model_.componentIndex(l, a) * nb_;
      const int row = lambda;  // law rows follow the λ layout
      for (const AttachmentTerm& term : attached.attachment.row(a))
        for (int t = 0; t < nb_; ++t) all.emplace_back(term.dof * nb_ + t, lambda + t, 0.0);
      for (int b = 0; b < d; ++b) {
        const int lambda_b = dynamic_rows_ + model_.componentIndex(l, b) * nb_;
        for (int c = 0; c < nb_; ++c)
          for (int r = 0; r < nb_; ++r) {
            for (const AttachmentTerm& term : attached.attachment.row(b))
              all.emplace_back(row + r, term.dof * nb_ + c, 0.0);
            all.emplace_back(row + r, lambda_b + c, 0.0);
          }
      }
    }
  }
  deadline.check(step + "sorting the Jacobian pattern");
  pattern_.resize(size_, size_);
  pattern_.setFromTriplets(all.begin(), all.end());
  pattern_.makeCompressed();

  deadline.check(step + "locating the dynamics entries");
  operator_slot_.resize(dynamics.size());
  jacobian_slot_.resize(dynamics.size());
  for (size_t e = 0; e < dynamics.size(); ++e) {
    if (e % (1u << 20) == 0)  // millions of entries: checked every 2^20
      deadline.check(step + "locating the dynamics entries, " + std::to_string(e) + " of " +
                     std::to_string(dynamics.size()) + " done");
    operator_slot_[e] = slotOf(linear_operator_, dynamics[e].row(), dynamics[e].col());
    jacobian_slot_[e] = slotOf(pattern_, dynamics[e].row(), dynamics[e].col());
  }
  constant_values_.setZero(pattern_.nonZeros());
  values_.setZero(pattern_.nonZeros());
  displacement_slots_.assign(laws_.lawCount(), {});
  force_slots_.assign(laws_.lawCount(), {});
  for (int l = 0; l < laws_.lawCount(); ++l) {
    deadline.check(step + "locating the law entries, " + law(l) + " done");
    const AttachedLaw& attached = laws_.law(l);
    const int d = laws_.dimension(l);
    const double sign = attached.law->forceSign();
    const LawAttachment& w = attached.attachment;
    displacement_slots_[l].assign(d * d, {});
    force_slots_[l].assign(d * d, std::vector<int>(nb_ * nb_));
    for (int a = 0; a < d; ++a) {
      const int row = dynamic_rows_ + model_.componentIndex(l, a) * nb_;
      // Dynamics: − sign W_aj λ_a on each DOF j of the law's row a (constant).
      for (const AttachmentTerm& term : w.row(a))
        for (int t = 0; t < nb_; ++t)
          constant_values_[slotOf(pattern_, term.dof * nb_ + t, row + t)] -= sign * term.weight;
      for (int b = 0; b < d; ++b) {
        const int lambda_b = dynamic_rows_ + model_.componentIndex(l, b) * nb_;
        std::vector<int>& ds = displacement_slots_[l][a * d + b];
        ds.assign(w.row(b).size() * nb_ * nb_, 0);
        for (size_t k = 0; k < w.row(b).size(); ++k)
          for (int c = 0; c < nb_; ++c)
            for (int r = 0; r < nb_; ++r)
              ds[k * nb_ * nb_ + c * nb_ + r] = slotOf(pattern_, row + r, w.row(b)[k].dof * nb_ + c);
        for (int c = 0; c < nb_; ++c)
          for (int r = 0; r < nb_; ++r) force_slots_[l][a * d + b][c * nb_ + r] = slotOf(pattern_, row + r, lambda_b + c);
      }
    }
  }
}

void FullSystem::setOmega(double omega) {
  if (!(omega > 0.0) || !std::isfinite(omega))
    throwInputError("omega", formatNumber(omega), "must be finite and > 0");
  const bool moved = omega != model_.omega;  // at construction ρ is set for this ω already
  model_.omega = omega;
  if (moved) setScaleFreeRhos();
  // A_k = [K − (kω)²M, kωC; −kωC, K − (kω)²M] per DOF pair (see LinearStructure).
  double* a = linear_operator_.valuePtr();
  size_t e = 0;
  const auto& ks = model_.basis.harmonics();
  const Eigen::Index entries = pattern_mass_.size();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int k = ks[h], w = harmonicWidth(k);
    const double kw = k * omega;
    for (Eigen::Index q = 0; q < entries; ++q) {
      const double diagonal = pattern_stiffness_[q] - kw * kw * pattern_mass_[q];
      const double coupling = kw * pattern_damping_[q];
      for (int ri = 0; ri < w; ++ri)
        for (int cj = 0; cj < w; ++cj) {
          const double value = ri == cj ? diagonal : (ri == 0 ? coupling : -coupling);
          a[operator_slot_[e]] = value;
          constant_values_[jacobian_slot_[e]] = value;
          ++e;
        }
    }
  }
}

bool FullSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                          Eigen::Ref<Eigen::VectorXd> g) {
  return evaluate(z, g, nullptr);
}

bool FullSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                     Eigen::Ref<Eigen::VectorXd> g,
                                     Eigen::Ref<Eigen::MatrixXd> jacobian) {
  const bool ok = evaluate(z, g, values_.data());
  denseFromPattern(pattern_, values_.data(), jacobian);  // small systems: the sparse values, dense
  return ok;
}

bool FullSystem::residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                           Eigen::Ref<Eigen::VectorXd> g,
                                           SparseMatrix& jacobian) {
  if (jacobian.rows() != size_ || jacobian.cols() != size_ ||
      jacobian.nonZeros() != pattern_.nonZeros() || !jacobian.isCompressed())
    throw std::invalid_argument("residualAndSparseJacobian: the matrix lacks the Jacobian pattern");
  return evaluate(z, g, jacobian.valuePtr());
}

bool FullSystem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& z,
                          Eigen::Ref<Eigen::VectorXd> g, double* values) {
  // Dynamics: A x − f − Σ sign_l λ_l on the law DOFs.
  g.head(dynamic_rows_).noalias() = linear_operator_ * z.head(dynamic_rows_);
  g.head(dynamic_rows_) -= forcing_;
  if (values) std::copy(constant_values_.data(), constant_values_.data() + constant_values_.size(), values);
  for (int l = 0; l < laws_.lawCount(); ++l) {
    const AttachedLaw& attached = laws_.law(l);
    const int d = laws_.dimension(l);
    const double sign = attached.law->forceSign();
    const LawAttachment& w = attached.attachment;
    for (int a = 0; a < d; ++a) {
      const int lambda = dynamic_rows_ + model_.componentIndex(l, a) * nb_;
      w.gatherCoefficients(z.data(), nb_, a, laws_.displacement(l).col(a).data());
      laws_.force(l).col(a) = z.segment(lambda, nb_);
      w.scatterCoefficients(z.data() + lambda, nb_, a, -sign, g.data());
    }
    if (!laws_.evaluate(l, model_.omega, values != nullptr)) return false;
    for (int a = 0; a < d; ++a) {
      const int row = dynamic_rows_ + model_.componentIndex(l, a) * nb_;
      g.segment(row, nb_) = laws_.residual(l).col(a);
      if (!values) continue;
      for (int b = 0; b < d; ++b) {
        const double* displacement = laws_.displacementBlock(l, a, b).data();
        const double* force = laws_.forceBlock(l, a, b).data();
        const std::vector<int>& ds = displacement_slots_[l][a * d + b];
        const std::vector<int>& fs = force_slots_[l][a * d + b];
        for (int e = 0; e < nb_ * nb_; ++e) values[fs[e]] += force[e];
        const std::vector<AttachmentTerm>& terms = w.row(b);
        for (size_t k = 0; k < terms.size(); ++k) {
          const int* slot = ds.data() + k * nb_ * nb_;
          for (int e = 0; e < nb_ * nb_; ++e) values[slot[e]] += terms[k].weight * displacement[e];
        }
      }
    }
  }
  return g.allFinite();
}

void FullSystem::lawOmegaDerivative(Eigen::Ref<Eigen::VectorXd> column) {
  for (int l = 0; l < laws_.lawCount(); ++l) {
    const Eigen::MatrixXd& derivative = laws_.omegaDerivative(l, model_.omega);
    for (int a = 0; a < laws_.dimension(l); ++a)
      column.segment(dynamic_rows_ + model_.componentIndex(l, a) * nb_, nb_) = derivative.col(a);
  }
}

// ----------------------------------------------------------- condensed system

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

std::unique_ptr<HbSystem> makeHbSystem(const HbModel& model, bool condensed, LinearAlgebra algebra,
                                       const Deadline& deadline) {
  if (condensed) return std::make_unique<CondensedSystem>(model, algebra, deadline);
  return std::make_unique<FullSystem>(model, deadline);
}

}  // namespace eqhb
