#include "eqhb/accuracy/rung_test.h"

#include <chrono>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/error.h"
#include "eqhb/orbits/orbit_refinement.h"
#include "eqhb/orbits/smooth_flow.h"

namespace eqhb {

const char* accuracyTestName(AccuracyTest test) {
  return test == AccuracyTest::kExactOrbit ? "exact-orbit" : "estimate";
}

AccuracyTestChoice parseAccuracyTestChoice(const std::string& name) {
  if (name == "auto") return AccuracyTestChoice::kAuto;
  if (name == "estimate") return AccuracyTestChoice::kEstimate;
  throwInputError("accuracy_test", "\"" + name + "\"", "must be \"auto\" or \"estimate\"");
}

std::string exactOrbitUnavailable(const HbModel& model) {
  if (model.laws.empty()) return "no law";
  if (model.structure.dofs() > kExactOrbitMaxDofs)
    return std::to_string(model.structure.dofs()) + " DOFs, above the " + std::to_string(kExactOrbitMaxDofs) +
           " that shooting checks cheaply";
  // The same checks as a refinement by shooting: laws with an exact flow,
  // grounded, one per DOF.
  try {
    orbits::RefinementOptions refinement;
    refinement.validate(model);
    orbits::makeFlow(model, refinement.restitution);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

ExactOrbitError exactOrbitError(const HbModel& model, const Eigen::VectorXd& full) {
  const auto start = std::chrono::steady_clock::now();
  ExactOrbitError out;
  const auto flow = orbits::makeFlow(model, orbits::kHarmonicBalanceRestitution);
  const orbits::ShootingResult orbit = orbits::shootFromHarmonicBalance(*flow, model, full, orbits::ShootingOptions());
  out.converged = orbit.converged;
  if (orbit.converged) {
    out.exact_max_abs = orbit.max_abs;
    out.error = worstRelativeDifference(peakDisplacements(model, full), orbit.max_abs);
  } else {
    out.failure = "shooting did not converge: " + orbit.failure;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace eqhb
