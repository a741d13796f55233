// `solve --refine shoot`: harmonic balance followed by shooting
// (app::SolveOptions::refine, lib/eqhb/orbits/orbit_refinement.h). The answer
// becomes the exact periodic orbit: its Fourier truncation on the same
// harmonics and its exact max|x|.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "eqhb/app/solve_options.h"

namespace eqhb::cli {

struct RefineArguments {
  std::string method;        // --refine: "" (none) or "shoot"
  double restitution = app::SolveOptions{}.restitution;  // --restitution of contact laws, in [0, 1]
  int harmonics = 0;         // --refine-harmonics: the truncation's H (0: the solve's)
};

void addRefineOptions(CLI::App* command, RefineArguments& args);

}  // namespace eqhb::cli
