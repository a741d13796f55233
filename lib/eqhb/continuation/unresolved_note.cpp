#include "eqhb/continuation/unresolved_note.h"

#include "eqhb/harmonic_balance/force_resolution.h"

namespace eqhb {

std::string unresolvedForceClause(const HbModel& model, const std::vector<const CurvePoint*>& points) {
  const CurvePoint* worst = nullptr;
  double worst_rise = 0.0;
  for (const CurvePoint* p : points) {
    if (!p || !p->converged || p->harmonics != 0) continue;
    const auto force = worstUnresolvedForce(model, p->full);
    if (force && force->rise > worst_rise) {
      worst_rise = force->rise;
      worst = p;
    }
  }
  if (!worst) return "";
  HbModel at = model;
  at.omega = worst->omega;
  return "; " + unresolvedForceNote(at, worst->full);
}

}  // namespace eqhb
