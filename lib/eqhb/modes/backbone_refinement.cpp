#include "eqhb/modes/backbone_refinement.h"

#include <cmath>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/modes/mode_system.h"
#include "eqhb/modes/path_tracer.h"

namespace eqhb {

namespace {
// [x̂; λ̂; ω; ξ] of a recorded point.
Eigen::VectorXd unknowns(const BackbonePoint& p) {
  Eigen::VectorXd z(p.full.size() + 2);
  z << p.full, p.omega, p.xi;
  return z;
}
}  // namespace

int refineBackbone(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                   const StaticContactState* at_rest, double from, double to, int per_interval, Backbone* backbone) {
  const auto mode_system = makeModeSystem(model, backbone->start.shape, at_rest != nullptr, backbone->condensed);
  ModeSystem& system = *mode_system;
  std::vector<BackbonePoint> refined;
  int added = 0;
  const BackbonePoint* previous = nullptr;
  for (const BackbonePoint& p : backbone->points) {
    if (p.converged && previous && p.amplitude != previous->amplitude && previous->amplitude >= from &&
        previous->amplitude <= to && p.amplitude >= from && p.amplitude <= to) {
      const Eigen::VectorXd z0 = system.fromFullPoint(unknowns(*previous)), z1 = system.fromFullPoint(unknowns(p));
      const double s0 = std::log(previous->amplitude), s1 = std::log(p.amplitude);
      for (int j = 1; j <= per_interval; ++j) {
        const double t = static_cast<double>(j) / (per_interval + 1);
        const double a = std::exp(s0 + t * (s1 - s0));
        const Eigen::VectorXd guess = z0 + t * (z1 - z0);
        system.setAmplitude(a);
        system.prepareAt(guess[system.omegaIndex()]);
        const SolverResult r = solver.solve(system, guess, solver_options);
        if (r.termination == Termination::kInvalidOptions) throw InputError("options: " + r.native_message);
        if (!r.converged()) continue;
        BackbonePoint q = describeModePoint(system, r.solution, a);
        q.converged = true;
        q.termination = terminationName(r.termination);
        q.iterations = r.iterations;
        q.residual_evaluations = r.residual_evaluations;
        q.jacobian_evaluations = r.jacobian_evaluations;
        q.seconds = r.seconds;
        refined.push_back(std::move(q));
        ++added;
      }
    }
    refined.push_back(p);
    if (p.converged) previous = &p;
  }
  backbone->points = std::move(refined);
  return added;
}

}  // namespace eqhb
