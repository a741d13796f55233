#include "eqhb/stability/hill_pencil.h"

#include <string>

#include "eqhb/error.h"

namespace eqhb {

HillPencilBuilder::HillPencilBuilder(const HbModel& model)
    : system_(model),
      jacobian_(system_.jacobianPattern()),
      g_(system_.size()),
      transform_(model.basis, model.samples),
      law_samples_(model.laws.size()),
      rate_(model.basis.size()),
      reading_(model.basis.size()),
      block_(model.basis.size(), model.basis.size()) {
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const Law& law = *model.laws[l].law;
    law_samples_[l].resize(model.samples, law.dimension(), law.historyTermsOn(model.samples));
  }
}

const HillPencil& HillPencilBuilder::build(const Eigen::VectorXd& full) {
  startPencil(full);
  addDynamicsRates();
  const bool force_rate = addLawRates(full);
  assemble(force_rate);
  return pencil_;
}

// J at `full`, A's triplets diag(J, I) and the pencil's sizes.
void HillPencilBuilder::startPencil(const Eigen::VectorXd& full) {
  const HbModel& model = system_.model();
  const int n0 = system_.size(), nx = model.structure.dofs() * model.basis.size();
  model.checkSolutionSize(full);
  system_.residualAndSparseJacobian(full, g_, jacobian_);
  pencil_.size = n0 + nx;
  pencil_.displacement_unknowns = nx;
  pencil_.jacobian_size = n0;
  a_.clear();
  b_.clear();
  a_.reserve(jacobian_.nonZeros() + nx);
  for (int j = 0; j < jacobian_.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(jacobian_, j); it; ++it) a_.emplace_back(it.row(), j, it.value());
  for (int i = 0; i < nx; ++i) a_.emplace_back(n0 + i, n0 + i, 1.0);
}

// Dynamics rows: J p + s (C ⊗ I + 2 M ⊗ D) p + s (M ⊗ I) w = 0, so B holds
// −(C ⊗ I + 2 M ⊗ D) on p and −M ⊗ I on w.
void HillPencilBuilder::addDynamicsRates() {
  const HbModel& model = system_.model();
  const int nb = model.basis.size(), n0 = pencil_.jacobian_size;
  const auto& ks = model.basis.harmonics();
  const LinearStructure& st = model.structure;
  for (int j = 0; j < st.damping.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(st.damping, j); it; ++it)
      for (int t = 0; t < nb; ++t) b_.emplace_back(it.row() * nb + t, j * nb + t, -it.value());
  for (int j = 0; j < st.mass.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(st.mass, j); it; ++it) {
      const int row = static_cast<int>(it.row()) * nb, col = j * nb;
      for (int t = 0; t < nb; ++t) b_.emplace_back(row + t, n0 + col + t, -it.value());
      // D on (a, b) of harmonic k: (kω b, −kω a).
      for (size_t h = 0; h < ks.size(); ++h) {
        if (ks[h] == 0) continue;
        const int o = model.basis.offset(static_cast<int>(h));
        const double kw = ks[h] * model.omega;
        b_.emplace_back(row + o, col + o + 1, -2.0 * it.value() * kw);
        b_.emplace_back(row + o + 1, col + o, 2.0 * it.value() * kw);
      }
    }
}

// The law rows' s-terms: P diag(Ψ_v) P and P diag(Ψ_λ̇) P per (a, b).
bool HillPencilBuilder::addLawRates(const Eigen::VectorXd& full) {
  const HbModel& model = system_.model();
  const int n = model.structure.dofs(), nb = model.basis.size();
  bool uses_force_rate = false;
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l) {
    const AttachedLaw& attached = model.laws[l];
    const Law& law = *attached.law;
    const int d = law.dimension();
    LawSamples& samples = law_samples_[l];
    for (int a = 0; a < d; ++a) {
      attached.attachment.gatherCoefficients(full.data(), nb, a, reading_.data());
      const double* x = reading_.data();
      const double* lambda = full.data() + (n + model.componentIndex(l, a)) * nb;
      transform_.synthesize(x, samples.displacement.col(a).data());
      transform_.differentiate(x, model.omega, rate_.data());
      transform_.synthesize(rate_.data(), samples.velocity.col(a).data());
      transform_.synthesize(lambda, samples.force.col(a).data());
      transform_.differentiate(lambda, model.omega, rate_.data());
      transform_.synthesize(rate_.data(), samples.force_rate.col(a).data());
    }
    law.evaluate(samples, true);
    for (int a = 0; a < d; ++a) {
      const int row = (n + model.componentIndex(l, a)) * nb;
      for (int bi = 0; bi < d; ++bi) {
        const int ab = a * d + bi;
        if (law.usesVelocity()) {
          transform_.gram(samples.dpsi_dvelocity.col(ab).data(), block_);
          for (int c = 0; c < nb; ++c)
            for (int r = 0; r < nb; ++r)
              if (block_(r, c) != 0.0)
                for (const AttachmentTerm& term : attached.attachment.row(bi))
                  b_.emplace_back(row + r, term.dof * nb + c, -(term.weight * block_(r, c)));
        }
        if (law.usesForceRate()) {
          uses_force_rate = true;
          transform_.gram(samples.dpsi_dforce_rate.col(ab).data(), block_);
          const int lambda_b = (n + model.componentIndex(l, bi)) * nb;
          for (int c = 0; c < nb; ++c)
            for (int r = 0; r < nb; ++r)
              if (block_(r, c) != 0.0) b_.emplace_back(row + r, lambda_b + c, -block_(r, c));
        }
      }
    }
  }
  return uses_force_rate;
}

// The identity rows w − s p = 0, then A and B̃ (B on its nonzero columns).
void HillPencilBuilder::assemble(bool force_rate) {
  const int n0 = pencil_.jacobian_size, nx = pencil_.displacement_unknowns;
  for (int i = 0; i < nx; ++i) b_.emplace_back(n0 + i, i, 1.0);
  std::vector<int>& columns = pencil_.columns;
  columns.clear();
  for (int i = 0; i < nx; ++i) columns.push_back(i);
  for (int i = 0; i < nx; ++i) columns.push_back(n0 + i);
  if (force_rate)
    for (int i = nx; i < n0; ++i) columns.push_back(i);
  position_.assign(pencil_.size, -1);
  for (size_t c = 0; c < columns.size(); ++c) position_[columns[c]] = static_cast<int>(c);
  b_kept_.clear();
  b_kept_.reserve(b_.size());
  for (const Triplet& e : b_)
    if (position_[e.col()] >= 0) b_kept_.emplace_back(e.row(), position_[e.col()], e.value());

  pencil_.a.resize(pencil_.size, pencil_.size);
  pencil_.a.setFromTriplets(a_.begin(), a_.end());
  pencil_.b_columns.resize(pencil_.size, static_cast<int>(columns.size()));
  pencil_.b_columns.setFromTriplets(b_kept_.begin(), b_kept_.end());
}

}  // namespace eqhb
