// `eqhb sweep`: a frequency-response curve by continuation in ω.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "eqhb/app/sweep.h"
#include "solve_command.h"

namespace eqhb::cli {

struct SweepArguments {
  // The range, steps and point limit (the solver's choice and checks come
  // from SolveArguments).
  app::SweepOptions curve;
  std::string out;    // CSV file
  std::string chart;  // PNG/SVG prefix
  std::string hdf5;   // HDF5 file of the curve
  bool json = false;  // the curve as one JSON object on stdout, with each point's coefficients
  bool log_amplitude = false;  // chart: logarithmic amplitude axis
};

void addSweepCommand(CLI::App& app, SolveArguments& solve, SweepArguments& sweep);
int runSweep(const SolveArguments& solve, const SweepArguments& sweep);

}  // namespace eqhb::cli
