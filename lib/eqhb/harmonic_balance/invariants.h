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
// period for the check (default: 8 times the model's N). Each measure is
// relative to its channel, floored at a fraction of the problem's own
// scales (Law::violations), those convergence is measured in.
std::vector<LawInvariants> checkInvariants(const HbModel& model, const Eigen::VectorXd& full,
                                           int samples = 0);
std::vector<LawInvariants> checkInvariants(const HbModel& model, const Eigen::VectorXd& full,
                                           const PhysicalScales& scales, int samples = 0);

// The problem's scales at the model's ω (problem_scales.h): the linear
// response at the laws' DOFs, or the loads and stiffness where A_k is singular.
PhysicalScales invariantScales(const HbModel& model);

}  // namespace eqhb
