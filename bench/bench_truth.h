// What each benchmark scene is checked against: a time-domain reference run
// to steady state, and the scene solved with 4x its harmonics.
#pragma once

#include <Eigen/Dense>
#include <filesystem>
#include <string>
#include <vector>

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
};

// The references of the scene at `path`: its 4x-H solution by continuation
// from its own H, and a time run of `step` for at most `max_periods` periods.
Truth buildTruth(const std::filesystem::path& path, double step, int max_periods);

// What the report says of a scene's references.
struct TruthStatus {
  std::string scene;
  bool periodic;
  int periods;
  double change, seconds;
  bool used, high;
};

TruthStatus truthStatus(const Truth& truth);
std::string truthTable(const std::vector<TruthStatus>& truths);

}  // namespace eqhb::bench
