// `eqhb modes`: a scene's nonlinear mode K followed in modal amplitude
// (app::modes): ω, damping ratio, dissipated energy and shape per amplitude.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "eqhb/app/modes.h"
#include "solve_command.h"

namespace eqhb::cli {

struct ModesArguments {
  SolveArguments solve;  // scene, backend and its limits (the solve flags modes shares)
  // Mode, amplitude range, points, time limit and synthesis (the backend and
  // its options come from `solve`).
  app::ModesOptions modes;
  bool csv = false;
  std::string hdf5;  // HDF5 file of the backbone
};

void addModesCommand(CLI::App& app, ModesArguments& args);
// Exit code: 0 every point converged, 1 otherwise.
int runModes(const ModesArguments& args);

}  // namespace eqhb::cli
