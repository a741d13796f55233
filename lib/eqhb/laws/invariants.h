// Physical checks of a harmonic-balance solution, sampled densely in time:
// each law reports its own named worst violations (Law::violations).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <utility>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

struct LawInvariants {
  int law = 0;  // index into model.laws
  std::string type;
  std::vector<std::pair<std::string, double>> violations;
};

// full: [x; λ] coefficients (FullSystem layout). samples: time samples per
// period for the check (default: 8 times the model's N).
std::vector<LawInvariants> checkInvariants(const HbModel& model, const Eigen::VectorXd& full,
                                           int samples = 0);

}  // namespace eqhb
