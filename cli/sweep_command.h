// `eqhb sweep`: a frequency-response curve by continuation in ω.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "solve_command.h"

namespace eqhb::cli {

struct SweepArguments {
  std::optional<double> from, to;  // default: the scene's [sweep]
  std::optional<double> step;  // default: ContinuationOptions::defaultStep
  std::optional<double> min_step, max_step;  // default: min(1e-6, step), max(0.1, step)
  bool arclength = false;
  int max_points = 20000;
  std::string out;    // CSV file
  std::string chart;  // PNG/SVG prefix
  std::string hdf5;   // HDF5 file of the curve
  bool json = false;  // the curve as one JSON object on stdout, with each point's coefficients
  bool log_amplitude = false;  // chart: logarithmic amplitude axis
};

void addSweepCommand(CLI::App& app, SolveArguments& solve, SweepArguments& sweep);
int runSweep(const SolveArguments& solve, const SweepArguments& sweep);

}  // namespace eqhb::cli
