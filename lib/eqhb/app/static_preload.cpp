#include "eqhb/app/static_preload.h"

#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/preload/operating_point.h"

namespace eqhb::app {

void settleUnderPreload(Scene& scene) {
  if (scene.preload.empty()) return;
  auto solver = makeSolver("dogleg");
  try {
    scene.at_rest = solveStaticContact(scene.model, *solver, SolverOptions{});
  } catch (const InputError& e) {
    throw InputError(scene.source + ": " + e.what());
  }
  scene.model = anchoredAtRest(std::move(scene.model), *scene.at_rest);
}

}  // namespace eqhb::app
