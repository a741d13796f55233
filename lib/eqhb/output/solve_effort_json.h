// The effort of one solve as each point of a curve or a backbone reports it
// in JSON: how the solve ended, its iterations and evaluations, and its time.
// One writer for every point type that carries these fields (CurvePoint,
// BackbonePoint), so that the keys stay the same across outputs.
#pragma once

#include <nlohmann/json.hpp>

namespace eqhb::output {

template <class Point>
nlohmann::json solveEffortJson(const Point& p) {
  return {{"termination", p.termination},
          {"iterations", p.iterations},
          {"residual_evaluations", p.residual_evaluations},
          {"jacobian_evaluations", p.jacobian_evaluations},
          {"seconds", p.seconds}};
}

}  // namespace eqhb::output
