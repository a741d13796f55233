#include "eqhb/backends/registry.h"

#include <functional>
#include <initializer_list>

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

// A factory per variant of Backend, in the order given.
template <class Backend, class Variant>
void addVariants(std::vector<Factory>& all, std::initializer_list<Variant> variants) {
  for (Variant v : variants) all.push_back([v] { return std::make_unique<Backend>(v); });
}

std::vector<Factory> factories() {
  std::vector<Factory> all;
  addVariants<PowellDogleg>(all, {JacobianPolicy::kBroyden, JacobianPolicy::kEveryIteration});
#ifdef EQHB_WITH_MINPACK
  all.push_back([] { return std::make_unique<MinpackHybrj>(); });
#endif
#ifdef EQHB_WITH_CERES
  addVariants<CeresBackend>(all, {CeresStrategy::kLevenbergMarquardt, CeresStrategy::kDogleg,
                                  CeresStrategy::kSubspaceDogleg});
#endif
#ifdef EQHB_WITH_IPOPT
  addVariants<IpoptBackend>(all, {IpoptFormulation::kLeastSquares, IpoptFormulation::kSquare});
#endif
#ifdef EQHB_WITH_NLOPT
  addVariants<NloptBackend>(all, {NloptMethod::kLbfgs, NloptMethod::kSlsqp, NloptMethod::kNewuoa});
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
