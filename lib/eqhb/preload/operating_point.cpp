#include "eqhb/preload/operating_point.h"

#include "eqhb/error.h"

namespace eqhb {

Eigen::VectorXd operatingPoint(const HbModel& model, const StaticContactState& state) {
  if (!model.basis.contains(0))
    throwInputError("preload", "(harmonic_balance.set = \"odd\")",
                    "a static load needs the constant term: set = \"all\"");
  const int nb = model.basis.size(), n = model.structure.dofs();
  // Harmonic 0 is the first coefficient of each channel (harmonic_set.h).
  Eigen::VectorXd full = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nb) * (n + model.lawComponents()));
  for (int j = 0; j < n; ++j) full[j * nb] = state.displacement[j];
  for (int c = 0; c < model.lawComponents(); ++c) full[(n + c) * nb] = state.forces[c];
  return full;
}

HbModel anchoredAtRest(HbModel model, const StaticContactState& state) {
  for (size_t l = 0; l < model.laws.size(); ++l)
    if (auto anchored = model.laws[l].law->anchoredAt(state.rest[l])) model.laws[l].law = anchored;
  return model;
}

}  // namespace eqhb
