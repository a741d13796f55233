// The full harmonic-balance system on [x; λ] (hb_systems.h): its sparse
// Jacobian pattern, fixed at construction, A_k's values per ω and the
// residual with the law blocks.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/dense_from_pattern.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/harmonic_balance/system_memory.h"
#include "eqhb/size_limits.h"
#include "eqhb/sparse_slots.h"

namespace eqhb {

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

namespace {

// The set-up's progress, named in a TimeLimitReached: "set-up of the full
// system: <what>".
std::string setUpStep(const std::string& what) { return "set-up of the full system: " + what; }
// "3 of 10 harmonics"
std::string ofTotal(size_t i, size_t total, const char* things) {
  return std::to_string(i) + " of " + std::to_string(total) + " " + things;
}

}  // namespace

void FullSystem::buildPattern(const Deadline& deadline) {
  SparseMatrix p = model_.structure.pattern();
  p.makeCompressed();
  pattern_mass_ = valuesOnPattern(model_.structure.mass, p);
  pattern_damping_ = valuesOnPattern(model_.structure.damping, p);
  pattern_stiffness_ = valuesOnPattern(model_.structure.stiffness, p);
  const std::vector<Entry> dynamics = dynamicsEntries(p, deadline);
  deadline.check(setUpStep("sorting the dynamics pattern"));
  linear_operator_.resize(dynamic_rows_, dynamic_rows_);
  linear_operator_.setFromTriplets(dynamics.begin(), dynamics.end());
  linear_operator_.makeCompressed();
  buildJacobianPattern(dynamics, deadline);
  locateDynamicsEntries(dynamics, deadline);
  locateLawEntries(deadline);
}

// Entries of A in the loop order of setOmega: harmonic, entry of P, block.
std::vector<FullSystem::Entry> FullSystem::dynamicsEntries(const SparseMatrix& p, const Deadline& deadline) const {
  std::vector<Entry> dynamics;
  const auto& ks = model_.basis.harmonics();
  // Reserved: regrowing a vector of tens of millions of entries takes
  // seconds, between two checks of the time limit.
  std::size_t dynamic_entries = 0;
  for (int k : ks) dynamic_entries += static_cast<std::size_t>(harmonicWidth(k) * harmonicWidth(k)) * p.nonZeros();
  dynamics.reserve(dynamic_entries);
  for (size_t h = 0; h < ks.size(); ++h) {
    deadline.check(setUpStep("dynamics pattern, " + ofTotal(h, ks.size(), "harmonics") + " done"));
    const int w = harmonicWidth(ks[h]), o = model_.basis.offset(static_cast<int>(h));
    for (int j = 0; j < p.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(p, j); it; ++it)
        for (int ri = 0; ri < w; ++ri)
          for (int cj = 0; cj < w; ++cj)
            dynamics.emplace_back(static_cast<int>(it.row()) * nb_ + o + ri, j * nb_ + o + cj, 0.0);
  }
  return dynamics;
}

// The Jacobian's pattern: A's entries, −W on the law DOFs (the λ columns of
// the dynamics rows) and the law rows' blocks on their DOFs and components.
void FullSystem::buildJacobianPattern(const std::vector<Entry>& dynamics, const Deadline& deadline) {
  std::vector<Entry> all;
  std::size_t law_entries = 0;
  for (int l = 0; l < laws_.lawCount(); ++l)
    law_entries += static_cast<std::size_t>(laws_.dimension(l)) *
                   (laws_.law(l).attachment.dofs().size() * (nb_ + nb_ * nb_) + laws_.dimension(l) * nb_ * nb_);
  all.reserve(dynamics.size() + law_entries);
  all.insert(all.end(), dynamics.begin(), dynamics.end());
  for (int l = 0; l < laws_.lawCount(); ++l) {
    deadline.check(setUpStep("law pattern, " + ofTotal(l, laws_.lawCount(), "laws") + " done"));
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
  deadline.check(setUpStep("sorting the Jacobian pattern"));
  pattern_.resize(size_, size_);
  pattern_.setFromTriplets(all.begin(), all.end());
  pattern_.makeCompressed();
}

// Where each entry of A goes in linear_operator_ and in pattern_'s values.
void FullSystem::locateDynamicsEntries(const std::vector<Entry>& dynamics, const Deadline& deadline) {
  deadline.check(setUpStep("locating the dynamics entries"));
  operator_slot_.resize(dynamics.size());
  jacobian_slot_.resize(dynamics.size());
  for (size_t e = 0; e < dynamics.size(); ++e) {
    if (e % (1u << 20) == 0)  // millions of entries: checked every 2^20
      deadline.check(setUpStep("locating the dynamics entries, " + ofTotal(e, dynamics.size(), "done")));
    operator_slot_[e] = slotOf(linear_operator_, dynamics[e].row(), dynamics[e].col());
    jacobian_slot_[e] = slotOf(pattern_, dynamics[e].row(), dynamics[e].col());
  }
}

// The law blocks' slots in pattern_'s values and the constant −sign W entries.
void FullSystem::locateLawEntries(const Deadline& deadline) {
  constant_values_.setZero(pattern_.nonZeros());
  values_.setZero(pattern_.nonZeros());
  displacement_slots_.assign(laws_.lawCount(), {});
  force_slots_.assign(laws_.lawCount(), {});
  for (int l = 0; l < laws_.lawCount(); ++l) {
    deadline.check(setUpStep("locating the law entries, " + ofTotal(l, laws_.lawCount(), "laws") + " done"));
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

}  // namespace eqhb
