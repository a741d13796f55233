#include "eqhb/app/static_preload.h"

#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/preload/operating_point.h"

namespace eqhb::app {

void settleUnderPreload(Scene& scene) {
  if (scene.preload.empty()) return;
  // The library's dogleg, then the default path's backup backend (the
  // static problem's stick–slip kinks at rest stall the dogleg on chains of
  // rigid Coulomb contacts).
  auto dogleg = makeSolver("dogleg");
  auto backup = makeSolver(defaultBackupSolver("dogleg"));
  try {
    scene.at_rest = solveStaticContact(scene.model, {dogleg.get(), backup.get()}, SolverOptions{});
  } catch (const InputError& e) {
    throw InputError(scene.source + ": " + e.what());
  } catch (const StaticSolveFailed& e) {
    throw StaticSolveFailed(scene.source + ": " + e.what());
  }
  scene.model = anchoredAtRest(std::move(scene.model), *scene.at_rest);
}

}  // namespace eqhb::app
