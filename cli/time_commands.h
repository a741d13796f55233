// `eqhb simulate` (the nonsmooth time-domain reference) and `eqhb compare`
// (a harmonic-balance solve against it, with the error measures).
#pragma once

#include <CLI/CLI.hpp>

#include "eqhb/app/simulate.h"
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

// The settings given on the command line (app::timeOptionsFor puts them
// over the scene's [time_reference] and the general defaults).
app::TimeSettings timeSettings(const TimeArguments& time);

void addSimulateCommand(CLI::App& app, SolveArguments& solve, TimeArguments& time);
void addCompareCommand(CLI::App& app, SolveArguments& solve, TimeArguments& time);
int runSimulate(const SolveArguments& solve, const TimeArguments& time);
int runCompare(const SolveArguments& solve, const TimeArguments& time);

}  // namespace eqhb::cli
