// Links only eqhb::minpack (and through it eqhb::core): one adapter used
// directly, without the registry.
#include <iostream>

#include "eqhb/backends/minpack/minpack_hybrj.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: consumer_minpack SCENE\n";
    return 2;
  }
  const eqhb::Scene scene = eqhb::loadScene(argv[1]);
  auto system = eqhb::makeHbSystem(scene.model, true);
  eqhb::MinpackHybrj solver;
  const eqhb::SolverResult result =
      solver.solve(*system, Eigen::VectorXd::Zero(system->size()), eqhb::SolverOptions{});
  std::cout << scene.name << " by " << solver.name() << ": " << result.summary() << "\n";
  return result.converged() ? 0 : 1;
}
