// `eqhb study`: a grid or Latin-hypercube sample over scene values, each
// sample's resonance peak (--peak) or frequency response (--sweep), on the
// threads of one machine or, launched by mpirun/srun, on MPI ranks.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "solve_command.h"

namespace eqhb::cli {

struct StudyArguments {
  std::vector<std::string> vary;  // PATH=FROM:TO:COUNT
  std::optional<int> lhs;         // Latin hypercube of this many samples
  unsigned long long seed = 1;
  bool sweep = false, peak = false;
  std::optional<double> from, to;  // default: the scene's [sweep]
  double step = 0.01;              // --sweep grid step
  std::string dof = "1";           // by number from 1 or name ("w60")
  int coarse_points = 41;
  int max_peaks = 4;
  int threads = 0;                 // 0: every core
  std::string out;
  std::string chart;               // PREFIX of the design chart (plot_study.py)
  std::string hdf5;                // HDF5 file of the samples
};

void addStudyCommand(CLI::App& app, SolveArguments& solve, StudyArguments& study);
// 0 when every sample succeeded, 1 when some failed (listed), 2 bad input.
int runStudy(const SolveArguments& solve, const StudyArguments& study);

}  // namespace eqhb::cli
