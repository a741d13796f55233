// SpringLawMonodromy's product in the phases' modal coordinates (its
// header): the modes of A₁₁ per set of laws' states, and the chain of
// phases carried in the modes each phase leaves.
#include <algorithm>
#include <cmath>

#include "eqhb/stability/spring_law_monodromy.h"

namespace eqhb {

// A₁₁ = V D V⁻¹, and for each stuck slider l the displacement its anchor
// column B_l holds: A₁₁⁻¹ B_l = [−k_t K⁻¹ w; 0] (the static deflection of a
// unit anchor move, K with the stuck and closed springs in), so that
// A₁₁ x + B z = A₁₁ (x + A₁₁⁻¹ B z). Decomposed once per set of states: the
// same sets come back from point to point whatever slips elsewhere.
const SpringLawMonodromy::ActiveModes& SpringLawMonodromy::activeModes(const std::vector<char>& active) {
  auto found = modes_.find(active);
  if (found != modes_.end()) return found->second;
  ActiveModes modes;
  Eigen::MatrixXd stiffness;
  modes.exponential = PhaseExponential(structuralGenerator(active, stiffness));
  modes.anchor_shift = Eigen::MatrixXd::Zero(2 * m_, laws_);
  for (int l = 0; l < laws_; ++l)
    if (active[l] == kHeld && !contact_[l]) modes.sliders.push_back(l);
  modes.usable = modes.exponential.decomposed();
  if (modes.usable && !modes.sliders.empty()) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(stiffness);
    // A singular K (a free structure) leaves A₁₁ singular: the anchors
    // then have no static deflection and the whole A is used instead.
    modes.usable = lu.rcond() > 1e-12;
    for (int l : modes.sliders) modes.anchor_shift.col(l).head(m_) = -spring_[l] * lu.solve(direction_[l]);
  }
  if (modes.usable) modes.anchor_modes = modes.exponential.inverse() * modes.anchor_shift;
  return modes_.emplace(active, std::move(modes)).first->second;
}

// Π over the phases of R_j exp(A_j τ_j) in the coordinates a_j = V_j⁻¹ (x +
// A₁₁⁻¹ B z) and z, where a phase only scales a_j (exp(D τ)) and leaves z.
// A mode a phase damps below PhaseExponential::kNegligibleGrowth is gone
// after it: the product keeps, per phase, the leading modes that outlast it
// (kept_). Its eigenvalues are those of the cyclic product started at any
// phase, so it starts at the phase that keeps the fewest, p, with the
// columns of a_p's kept modes and z: a matrix of that size whose
// eigenvalues are the multipliers (the rest are 0). A switch from phase q to
// r maps x = V_q a_q − A₁₁⁻¹B_q z, resets an anchor (z_s = wᵀδq, (4)), and
// a_r = V_r⁻¹ x + V_r⁻¹ A₁₁⁻¹B_r z on r's kept rows only.
void SpringLawMonodromy::chainLeadingModes(double period) {
  const size_t phases = switches_.size();
  const Eigen::Index two_m = 2 * m_, size = 2 * m_ + laws_;
  if (modal_.rows() != two_m) {
    modal_.resize(two_m, size);
    anchors_.resize(laws_, size);
    physical_.resize(two_m, size);
    reduced_.resize(size, size);
  }
  phase_length_.resize(phases);
  kept_.resize(phases);
  size_t start = 0;
  for (size_t j = 0; j < phases; ++j) {
    phase_length_[j] = phaseLength(j, period);
    kept_[j] = phase_modes_[j]->exponential.survivingModes(phase_length_[j]);
    if (kept_[j] < kept_[start]) start = j;
  }
  const Eigen::Index columns = kept_[start] + sliders_;
  Eigen::Index rows = kept_[start];
  auto a = [&](Eigen::Index r) { return modal_.topLeftCorner(r, columns); };
  auto z = anchors_.topLeftCorner(sliders_, columns);
  auto x = physical_.topLeftCorner(two_m, columns);
  a(rows).setZero();
  a(rows).leftCols(rows).setIdentity();
  z.setZero();
  z.rightCols(sliders_).setIdentity();
  for (size_t k = 0; k < phases; ++k) {
    const size_t q = (start + k) % phases, r = (q + 1) % phases;
    const ActiveModes &from = *phase_modes_[q], &to = *phase_modes_[r];
    // Phase p's own scaling comes last, round the period.
    if (k > 0) from.exponential.scaleModes(phase_length_[q], a(rows));
    x.noalias() = from.exponential.vectors().leftCols(rows) * a(rows);
    for (int l : from.sliders)
      if (slot_[l] >= 0) x.noalias() -= from.anchor_shift.col(l) * z.row(slot_[l]);
    const Switch& s = switches_[r];
    if (resetsAnchor(s)) resetAnchor(s, x, z.row(slot_[s.law]));
    rows = kept_[r];
    a(rows).noalias() = to.exponential.inverse().topRows(rows) * x;
    for (int l : to.sliders)
      if (slot_[l] >= 0) a(rows).noalias() += to.anchor_modes.col(l).head(rows) * z.row(slot_[l]);
  }
  phase_modes_[start]->exponential.scaleModes(phase_length_[start], a(rows));
  reduced_.topLeftCorner(rows, columns) = a(rows);
  reduced_.block(rows, 0, sliders_, columns) = z;
  eigenvaluesOf(reduced_.topLeftCorner(columns, columns), two_m + sliders_);
}

}  // namespace eqhb
