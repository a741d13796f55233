#include "failure_maps.h"

#include <iostream>
#include <memory>
#include <random>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/backends/registry.h"

namespace eqhb::bench {

namespace {

FailureRow solveOnce(const Scene& scene, const std::string& grid, const std::string& value, int seed,
                     const std::string& solver_name, const Eigen::VectorXd* start, bool condensed) {
  FailureRow row;
  row.scene = scene.name;
  row.grid = grid;
  row.solver = solver_name;
  row.value = value;
  row.seed = seed;
  try {
    auto system = makeHbSystem(scene.model, condensed);
    SolverOptions options;
    options.time_limit = 1.0;
    const Eigen::VectorXd z0 = start ? *start : Eigen::VectorXd::Zero(system->size());
    const SolverResult r = makeSolver(solver_name)->solve(*system, z0, options);
    row.converged = r.converged();
    row.termination = terminationName(r.termination);
    row.iterations = r.iterations;
    row.seconds = r.seconds;
  } catch (const std::exception& e) {
    row.termination = "not_applicable";
  }
  return row;
}

}  // namespace

std::vector<FailureRow> failureMaps(const std::filesystem::path& path, const std::vector<std::string>& solvers,
                                    bool quick) {
  std::vector<FailureRow> rows;
  const Scene base = loadScene(path.string());
  // The system the own dogleg solves from a cold start (condensed if it
  // can), and its solution as the centre of the perturbed starts.
  bool condensed = true;
  SolverResult solved;
  for (bool c : {true, false}) {
    auto system = makeHbSystem(base.model, c);
    solved = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
    condensed = c;
    if (solved.converged()) break;
  }
  const std::vector<double> sigmas = quick ? std::vector<double>{0.1, 1.0} : std::vector<double>{0.01, 0.1, 0.3, 1.0, 3.0};
  const int seeds = quick ? 2 : 5;
  for (const auto& solver : solvers) {
    rows.push_back(solveOnce(base, "start", "cold", 0, solver, nullptr, condensed));
    if (solved.converged()) {
      const double rms = solved.solution.norm() / std::sqrt(static_cast<double>(solved.solution.size()));
      for (double sigma : sigmas)
        for (int seed = 1; seed <= seeds; ++seed) {
          std::mt19937 rng(seed);
          std::normal_distribution<double> normal;
          Eigen::VectorXd z0 = solved.solution;
          for (Eigen::Index i = 0; i < z0.size(); ++i) z0[i] += sigma * rms * normal(rng);
          rows.push_back(solveOnce(base, "start", formatNumber(sigma), seed, solver, &z0, condensed));
        }
    }
    for (int h : quick ? std::vector<int>{5, 40} : std::vector<int>{5, 10, 20, 40, 80}) {
      const int samples = std::max(base.model.samples, 16 * h);
      const Scene s = loadScene(path.string(), {"harmonic_balance.harmonics=" + std::to_string(h),
                                                "harmonic_balance.samples=" + std::to_string(samples)});
      rows.push_back(solveOnce(s, "harmonics", std::to_string(h), 0, solver, nullptr, condensed));
    }
    for (double rho : quick ? std::vector<double>{0.1, 10.0} : std::vector<double>{0.01, 0.1, 1.0, 10.0, 100.0}) {
      const auto set = lawOverrides(base.model, "rho", formatNumber(rho));
      if (!set.empty())
        rows.push_back(solveOnce(loadScene(path.string(), set), "rho", formatNumber(rho), 0, solver, nullptr, condensed));
    }
    for (double scale : quick ? std::vector<double>{0.5, 2.0} : std::vector<double>{0.25, 0.5, 1.0, 2.0, 4.0}) {
      std::vector<std::string> set;
      for (size_t i = 0; i < base.model.structure.loads.size(); ++i) {
        const auto& load = base.model.structure.loads[i];
        const std::string f = "forcing[" + std::to_string(i) + "].";
        set.push_back(f + "cos=" + formatNumber(scale * load.cos_amplitude));
        set.push_back(f + "sin=" + formatNumber(scale * load.sin_amplitude));
      }
      rows.push_back(solveOnce(loadScene(path.string(), set), "forcing", formatNumber(scale), 0, solver, nullptr, condensed));
    }
    std::cerr << "  failure maps " << base.name << " (" << (condensed ? "condensed" : "full") << ") " << solver
              << " done\n";
  }
  return rows;
}

}  // namespace eqhb::bench
