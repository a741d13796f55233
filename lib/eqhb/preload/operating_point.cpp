#include "eqhb/preload/operating_point.h"

#include <Eigen/UmfPackSupport>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"

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

Eigen::VectorXd linearisedStart(const HbModel& model, const StaticContactState& state,
                                const SolverOptions& options) {
  const Eigen::VectorXd at_rest = operatingPoint(model, state);
  try {
    auto full = makeHbSystem(model, false, options.linear_algebra);
    const Eigen::VectorXd z = full->fromFullCoefficients(at_rest);
    Eigen::VectorXd g(z.size());
    SparseMatrix jacobian = full->jacobianPattern();
    if (!full->residualAndSparseJacobian(z, g, jacobian)) return at_rest;
    const Eigen::UmfPackLU<SparseMatrix> lu(jacobian);
    if (lu.info() != Eigen::Success) return at_rest;  // singular: no linear response
    const Eigen::VectorXd step = lu.solve(g);
    if (lu.info() != Eigen::Success || !step.allFinite()) return at_rest;
    return full->fullCoefficients(z - step);
  } catch (const std::exception&) {  // a singular A_k, memory: the operating point as it is
  }
  return at_rest;
}

HbModel anchoredAtRest(HbModel model, const StaticContactState& state) {
  for (size_t l = 0; l < model.laws.size(); ++l)
    if (auto anchored = model.laws[l].law->anchoredAt(state.rest[l])) model.laws[l].law = anchored;
  return model;
}

}  // namespace eqhb
