// Choosing a backend in C++: a structure built in code (the 2-DOF chain of
// friction-1d with exact Coulomb friction on DOF 2), its condensed
// harmonic-balance system, and every registered backend solving it from
// rest with the same options. Prints one line per backend.
#include <chrono>
#include <cstdio>
#include <memory>

#include "eqhb/backends/registry.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/coulomb_1d.h"

int main() {
  // M ẍ + C ẋ + K x = f cos ωt + W λ: two unit masses, K = k [[2, −1], [−1, 1]].
  Eigen::MatrixXd K(2, 2);
  K << 2.0, -1.0, -1.0, 1.0;
  const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::MatrixXd C = 0.02 * K;
  eqhb::HarmonicLoad load;  // 20 cos ωt on DOF 1 (0-based 0)
  load.dof = 0;
  load.cos_amplitude = 20.0;

  eqhb::HbModel model;
  model.structure = eqhb::LinearStructure::fromMassStiffnessDamping(M, K, C, {load});
  // Coulomb friction μN = 7.2 on DOF 2, min/max form, ρ = 1.
  model.laws.push_back({{1}, std::make_shared<eqhb::Coulomb1D>(7.2, eqhb::CoulombForm::kMinMax)});
  model.basis = eqhb::HarmonicSet(eqhb::HarmonicKind::kOdd, 10);  // harmonics 1, 3, ..., 19
  model.samples = 1024;
  model.omega = 0.4;
  model.validate();  // throws InputError naming the field

  auto system = eqhb::makeHbSystem(model, /*condensed=*/true);
  eqhb::SolverOptions options;  // tolerance 1e-10 on the scaled residual
  std::printf("%-22s %-14s %5s %6s %12s %10s\n", "backend", "termination", "iter", "evals", "max|x2|", "ms");
  for (const eqhb::SolverEntry& entry : eqhb::registeredSolvers()) {
    auto solver = eqhb::makeSolver(entry.name);
    const auto began = std::chrono::steady_clock::now();
    const eqhb::SolverResult result = solver->solve(*system, Eigen::VectorXd::Zero(system->size()), options);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
    const eqhb::HbSolution solution = eqhb::summarize(model, system->fullCoefficients(result.solution));
    std::printf("%-22s %-14s %5d %6d %12.6f %10.2f\n", entry.name.c_str(), eqhb::terminationName(result.termination),
                result.iterations, result.residual_evaluations, solution.displacements[1].max_abs, ms);
  }
  return 0;
}
