// Loads a scene, solves it with a backend chosen by name and prints the result:
// exit 0 only when the solve converged.
#include <iostream>

#include "eqhb/backends/registry.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/version.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: consumer SCENE SOLVER\n";
    return 2;
  }
  std::cout << "eqhb " << EQHB_VERSION << ", solvers:";
  for (const auto& entry : eqhb::registeredSolvers()) std::cout << " " << entry.name;
  std::cout << "\n";
  const eqhb::Scene scene = eqhb::loadScene(argv[1]);
  auto system = eqhb::makeHbSystem(scene.model, true);
  auto solver = eqhb::makeSolver(argv[2]);
  const eqhb::SolverResult result =
      solver->solve(*system, Eigen::VectorXd::Zero(system->size()), eqhb::SolverOptions{});
  const eqhb::HbSolution solution = eqhb::summarize(scene.model, system->fullCoefficients(result.solution));
  std::cout << scene.name << ": " << result.summary() << "\n";
  for (const auto& c : solution.displacements) std::cout << "  max|" << c.label << "| = " << c.max_abs << "\n";
  return result.converged() ? 0 : 1;
}
