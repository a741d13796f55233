#include "registry.h"

#include <functional>

#include "dogleg/powell_dogleg.h"
#include "eqhb/error.h"
#ifdef EQHB_WITH_MINPACK
#include "minpack/minpack_hybrj.h"
#endif

namespace eqhb {

namespace {
using Factory = std::function<std::unique_ptr<Solver>()>;

std::vector<Factory> factories() {
  std::vector<Factory> all = {
      [] { return std::make_unique<PowellDogleg>(JacobianPolicy::kBroyden); },
      [] { return std::make_unique<PowellDogleg>(JacobianPolicy::kEveryIteration); },
  };
#ifdef EQHB_WITH_MINPACK
  all.push_back([] { return std::make_unique<MinpackHybrj>(); });
#endif
  return all;
}
}  // namespace

std::vector<SolverEntry> registeredSolvers() {
  std::vector<SolverEntry> entries;
  for (const auto& make : factories()) {
    auto solver = make();
    entries.push_back({solver->name(), solver->description()});
  }
  return entries;
}

std::unique_ptr<Solver> makeSolver(const std::string& name) {
  std::string known;
  for (const auto& make : factories()) {
    auto solver = make();
    if (solver->name() == name) return solver;
    known += (known.empty() ? "" : ", ") + solver->name();
  }
  throwInputError("solver", "\"" + name + "\"", "unknown; available: " + known);
}

}  // namespace eqhb
