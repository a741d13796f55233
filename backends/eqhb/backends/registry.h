// Backends by name, for the library API, the CLI and the benchmark. Only the
// backends compiled in (CMake options EQHB_WITH_*) are listed.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "eqhb/solvers/solver.h"

namespace eqhb {

struct SolverEntry {
  std::string name;
  std::string description;
};

std::vector<SolverEntry> registeredSolvers();
// Throws InputError naming the unknown solver and listing the known ones.
std::unique_ptr<Solver> makeSolver(const std::string& name);

}  // namespace eqhb
