#include "eqhb/modes/backbone.h"

#include <chrono>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/modes/mode_system.h"
#include "eqhb/modes/path_tracer.h"
#include "eqhb/modes/sliding_branch.h"

namespace eqhb {

void BackboneOptions::validate(int modes) const {
  if (mode < 1 || mode > modes)
    throwInputError("mode", std::to_string(mode),
                    "must be in [1, " + std::to_string(modes) + "]: the linearised structure has " +
                        std::to_string(modes) + " mode(s)");
  if (!(from > 0.0) || !std::isfinite(from)) throwInputError("from", formatNumber(from), "must be finite and > 0");
  if (!(to > from) || !std::isfinite(to))
    throwInputError("to", formatNumber(to), "must be finite and > from (" + formatNumber(from) + ")");
  if (points < 2) throwInputError("points", std::to_string(points), "must be >= 2");
  if (max_halvings < 0) throwInputError("max_halvings", std::to_string(max_halvings), "must be >= 0");
  if (!(time_limit >= 0.0) || !std::isfinite(time_limit))
    throwInputError("time_limit", formatNumber(time_limit), "must be finite and >= 0 (seconds; 0 = none)");
}

const char* branchName(ModeBranch branch) { return branch == ModeBranch::kSliding ? "sliding" : "held"; }

double dissipatedEnergy(const HbModel& model, const Eigen::VectorXd& full, double omega, double xi) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  const Eigen::Map<const Eigen::MatrixXd> x(full.data(), nb, n);
  const Eigen::MatrixXd mass_x = x * model.structure.mass;
  const auto& ks = model.basis.harmonics();
  double sum = 0.0;
  for (size_t h = 0; h < ks.size(); ++h) {
    if (ks[h] == 0) continue;
    const int o = model.basis.offset(static_cast<int>(h));
    sum += ks[h] * ks[h] * (mass_x.row(o).dot(x.row(o)) + mass_x.row(o + 1).dot(x.row(o + 1)));
  }
  return xi * M_PI * omega * sum;
}

std::vector<LinearMode> startingModes(const HbModel& model, ModeBranch branch, const StaticContactState* at_rest) {
  if (branch == ModeBranch::kHeld) return linearModes(model, at_rest);
  HbModel free = model;
  free.laws.clear();
  return linearModes(free, nullptr);
}

Backbone followBackbone(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                        const BackboneOptions& o, const BackboneProgress& progress,
                        const StaticContactState* at_rest) {
  const auto start_time = std::chrono::steady_clock::now();
  const std::vector<LinearMode> modes = startingModes(model, o.branch, at_rest);
  o.validate(static_cast<int>(modes.size()));
  Backbone backbone;
  backbone.start = modes[o.mode - 1];
  backbone.branch = o.branch;
  backbone.condensed = o.condensed;
  const auto system = makeModeSystem(model, backbone.start.shape, at_rest != nullptr, o.condensed);
  if (o.branch == ModeBranch::kSliding)
    traceSlidingBranch(*system, solver, solver_options, o, progress, at_rest, &backbone);
  else
    tracePath(*system, solver, solver_options, o, progress, at_rest, &backbone);
  backbone.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return backbone;
}

}  // namespace eqhb
