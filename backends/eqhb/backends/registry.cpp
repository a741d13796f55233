#include "eqhb/backends/registry.h"

#include <functional>

#include "eqhb/backends/dogleg/powell_dogleg.h"
#include "eqhb/error.h"
#ifdef EQHB_WITH_MINPACK
#include "eqhb/backends/minpack/minpack_hybrj.h"
#endif
#ifdef EQHB_WITH_CERES
#include "eqhb/backends/ceres/ceres_backend.h"
#endif
#ifdef EQHB_WITH_IPOPT
#include "eqhb/backends/ipopt/ipopt_backend.h"
#endif
#ifdef EQHB_WITH_NLOPT
#include "eqhb/backends/nlopt/nlopt_backend.h"
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
#ifdef EQHB_WITH_CERES
  all.push_back([] { return std::make_unique<CeresBackend>(CeresStrategy::kLevenbergMarquardt); });
  all.push_back([] { return std::make_unique<CeresBackend>(CeresStrategy::kDogleg); });
  all.push_back([] { return std::make_unique<CeresBackend>(CeresStrategy::kSubspaceDogleg); });
#endif
#ifdef EQHB_WITH_IPOPT
  all.push_back([] { return std::make_unique<IpoptBackend>(IpoptFormulation::kLeastSquares); });
  all.push_back([] { return std::make_unique<IpoptBackend>(IpoptFormulation::kSquare); });
#endif
#ifdef EQHB_WITH_NLOPT
  all.push_back([] { return std::make_unique<NloptBackend>(NloptMethod::kLbfgs); });
  all.push_back([] { return std::make_unique<NloptBackend>(NloptMethod::kSlsqp); });
  all.push_back([] { return std::make_unique<NloptBackend>(NloptMethod::kNewuoa); });
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
