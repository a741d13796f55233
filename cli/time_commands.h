// `eqhb simulate` (the nonsmooth time-domain reference) and `eqhb compare`
// (a harmonic-balance solve against it, with the error measures).
#pragma once

#include <CLI/CLI.hpp>

#include "eqhb/references/time_integrator.h"
#include "eqhb/scenes/scene.h"
#include "solve_command.h"

namespace eqhb::cli {

struct TimeArguments {
  TimeOptions options;
  bool from_hb = false;    // simulate: start from the HB solution of the scene
  bool from_rest = false;  // compare: start from rest instead of the HB solution
  // The options as parsed, to tell given values from defaults: a value given
  // on the command line overrides the scene's [time_reference], a default
  // does not.
  CLI::Option *step = nullptr, *theta = nullptr, *periods = nullptr, *periodic_tolerance = nullptr;
};

// The run's time options: the general defaults, then the scene's
// [time_reference], then what the command line gave.
TimeOptions timeOptionsFor(const Scene& scene, const TimeArguments& time);

void addSimulateCommand(CLI::App& app, SolveArguments& solve, TimeArguments& time);
void addCompareCommand(CLI::App& app, SolveArguments& solve, TimeArguments& time);
int runSimulate(const SolveArguments& solve, const TimeArguments& time);
int runCompare(const SolveArguments& solve, const TimeArguments& time);

}  // namespace eqhb::cli
