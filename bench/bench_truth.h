// What each benchmark scene is checked against: a time-domain reference run
// to steady state (for a scene with a Signorini wall, its exact periodic
// orbit with elastic impacts instead), and the scene solved with 4x its
// harmonics.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "exact_reference.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/references/time_integrator.h"

namespace eqhb::bench {

// Period-to-period change below which a time run serves as reference.
constexpr double kUsableChange = 1e-4;

struct Truth {
  std::string scene;
  TimeReference reference;
  bool has_reference = false;
  HbModel high_model;
  Eigen::VectorXd high;  // converged 4x-H solution, empty if none
  // A Signorini wall: harmonic balance imposes no impact law, and as H grows
  // its answer approaches the orbit with elastic impacts (e = 1), not the
  // plastic one (e = 0) the time integrator's Moreau scheme would impose.
  // The reference is then that exact orbit (shooting), null elsewhere.
  std::shared_ptr<const ExactOrbit> exact;
  // The distance to that orbit of the harmonic balance at the scene's H
  // that started it (reference dogleg, continuation in H, ‖g‖ <= 1e-10;
  // NaN if it did not converge): the method's truncation error at that H.
  double truncation_error = NAN;
  int truncation_harmonics = 0;
};

// The references of the scene at `path`: its 4x-H solution by continuation
// from its own H, and a time run of `step` for at most `max_periods` periods.
Truth buildTruth(const std::filesystem::path& path, double step, int max_periods);

// What the report says of a scene's references.
struct TruthStatus {
  std::string scene;
  std::string kind;  // "time run" or "exact orbit, e = 1"
  bool periodic;
  int periods;
  double change, seconds;
  bool used, high;
};

TruthStatus truthStatus(const Truth& truth);
std::string truthTable(const std::vector<TruthStatus>& truths);

}  // namespace eqhb::bench
