#include "eqhb/stability/hill_reduction.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/stability/interface_reduction.h"

namespace eqhb {

Eigen::VectorXd HillReduction::reduce(const Eigen::VectorXd& full) const {
  model.checkSolutionSize(full, full_dofs);
  const int nb = model.basis.size(), m = model.structure.dofs();
  const Eigen::Index forces = full.size() - static_cast<Eigen::Index>(full_dofs) * nb;
  Eigen::VectorXd out(static_cast<Eigen::Index>(m) * nb + forces);
  // One channel after another: column i of X holds DOF i's coefficients.
  const Eigen::Map<const Eigen::MatrixXd> x(full.data(), nb, full_dofs);
  Eigen::Map<Eigen::MatrixXd>(out.data(), nb, m).noalias() = x * projection.transpose();
  out.tail(forces) = full.tail(forces);
  return out;
}

std::optional<HillReduction> reduceForHill(const HbModel& model, int above) {
  const int n = model.structure.dofs();
  if (above <= 0 || n <= above || model.laws.empty()) return std::nullopt;
  std::vector<int> boundary;
  for (const AttachedLaw& a : model.laws)
    for (int dof : a.attachment.dofs()) boundary.push_back(dof);
  const double fast_rate = kResolvedBandMargin * std::max(model.basis.highest(), 1) * model.omega;
  // decay 0: every damped mode above the band is dropped, whatever its
  // damping (Hill cannot resolve it either way); undamped ones stay.
  InterfaceReduction r;
  try {
    r = reduceToInterface(model.structure.mass, model.structure.damping, model.structure.stiffness, boundary,
                          fast_rate, 2.0 * M_PI / model.omega, 0.0);
  } catch (const InputError&) {
    return std::nullopt;  // a body held by its laws alone (K_ii singular): analysed as it is
  }
  if (r.modes_dropped == 0) return std::nullopt;
  HillReduction out;
  out.projection = std::move(r.projection);
  out.modes_kept = r.modes_kept;
  out.modes_dropped = r.modes_dropped;
  out.full_dofs = n;
  const int m = static_cast<int>(r.basis.cols());
  // Loads Tᵀ f: a load on DOF i acts on every q_j with T_ij ≠ 0 (the pencil
  // does not read them; the reduced model stays a model of the same forcing).
  std::vector<HarmonicLoad> loads;
  for (const HarmonicLoad& load : model.structure.loads)
    for (int j = 0; j < m; ++j)
      if (const double t = r.basis(load.dof, j); t != 0.0)
        loads.push_back({j, load.harmonic, t * load.cos_amplitude, t * load.sin_amplitude});
  out.model.structure = LinearStructure::fromMassStiffnessDamping(r.mass, r.stiffness, r.damping, loads);
  // Each law on the same rows, its DOFs renumbered to their place in q.
  std::vector<int> place(n, -1);
  for (size_t j = 0; j < r.boundary.size(); ++j) place[r.boundary[j]] = static_cast<int>(j);
  for (const AttachedLaw& a : model.laws) {
    std::vector<std::vector<AttachmentTerm>> rows;
    for (int c = 0; c < a.attachment.dimension(); ++c) {
      rows.emplace_back(a.attachment.row(c));
      for (AttachmentTerm& t : rows.back()) t.dof = place[t.dof];
    }
    out.model.laws.push_back({LawAttachment(std::move(rows)), a.law});
  }
  out.model.basis = model.basis;
  out.model.samples = model.samples;
  out.model.omega = model.omega;
  return out;
}

}  // namespace eqhb
