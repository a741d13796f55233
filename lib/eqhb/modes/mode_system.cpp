#include "eqhb/modes/mode_system.h"

#include "eqhb/modes/condensed_mode_system.h"
#include "eqhb/modes/full_mode_system.h"

namespace eqhb {

Eigen::VectorXd ModeSystem::fromFullPoint(const Eigen::VectorXd& full_point) const {
  const Eigen::Index full = full_point.size() - 2;
  Eigen::VectorXd z(size());
  z << fromFullCoefficients(full_point.head(full)), full_point.tail(2);
  return z;
}

std::unique_ptr<ModeSystem> makeModeSystem(const HbModel& model, const Eigen::VectorXd& shape, bool keep_static_loads,
                                           bool condensed) {
  if (condensed) return std::make_unique<CondensedModeSystem>(model, shape, keep_static_loads);
  return std::make_unique<FullModeSystem>(model, shape, keep_static_loads);
}

}  // namespace eqhb
