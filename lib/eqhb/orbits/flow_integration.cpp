#include "eqhb/orbits/flow_integration.h"

#include <cmath>

namespace eqhb::orbits {

bool validStart(const Eigen::VectorXd& y0, int size, double t0, double duration, FlowResult& result) {
  if (y0.size() == size && y0.allFinite() && duration >= 0.0 && std::isfinite(t0)) return true;
  result.failure = "initial state or interval not finite or of the wrong size";
  return false;
}

void prepareSamples(FlowSamples* samples, int dofs, int forces) {
  if (!samples) return;
  const int count = static_cast<int>(samples->times.size());
  samples->displacement.resize(count, dofs);
  samples->velocity.resize(count, dofs);
  samples->force.resize(count, forces);
}

void applySaltation(const Eigen::MatrixXd& reset, const Eigen::VectorXd& f_before, const Eigen::VectorXd& f_after,
                    const Eigen::RowVectorXd& gradient, double g_rate, Eigen::MatrixXd& jacobian) {
  if (g_rate != 0.0) {
    const Eigen::MatrixXd saltation = reset + (f_after - reset * f_before) * gradient / g_rate;
    jacobian = saltation * jacobian;
  } else {
    jacobian = reset * jacobian;
  }
}

}  // namespace eqhb::orbits
