#include "eqhb/preload/operating_point.h"

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

Eigen::VectorXd linearisedStart(const HbModel& model, const StaticContactState& state, Solver& solver,
                                const SolverOptions& options) {
  const Eigen::VectorXd at_rest = operatingPoint(model, state);
  try {
    auto full = makeHbSystem(model, false, options.linear_algebra);
    SolverOptions one = options;
    one.max_iterations = 1;
    const SolverResult step = solver.solve(*full, full->fromFullCoefficients(at_rest), one);
    if (step.solution.allFinite() && step.final_norm < step.initial_norm)
      return full->fullCoefficients(step.solution);
  } catch (const std::exception&) {  // a singular A_k or Jacobian, memory: the operating point as it is
  }
  return at_rest;
}

HbModel anchoredAtRest(HbModel model, const StaticContactState& state) {
  for (size_t l = 0; l < model.laws.size(); ++l)
    if (auto anchored = model.laws[l].law->anchoredAt(state.rest[l])) model.laws[l].law = anchored;
  return model;
}

}  // namespace eqhb
