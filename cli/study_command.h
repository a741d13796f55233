// `eqhb study`: a grid or Latin-hypercube sample over scene values, each
// sample's resonance peak (--peak) or frequency response (--sweep), on the
// threads of one machine or, launched by mpirun/srun, on MPI ranks.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/app/study.h"
#include "solve_command.h"

namespace eqhb::cli {

struct StudyArguments {
  // The sample, range, peak and folder options but the mode (set from
  // --sweep or --peak) and the solver's choice (from SolveArguments).
  app::StudyOptions study;
  bool sweep = false, peak = false;
  std::string chart;               // PREFIX of the design chart (plot_study.py)
  std::string hdf5;                // HDF5 file of the samples
};

void addStudyCommand(CLI::App& app, SolveArguments& solve, StudyArguments& study);
// 0 when every sample succeeded, 1 when some failed (listed), 2 bad input.
int runStudy(const SolveArguments& solve, const StudyArguments& study);

}  // namespace eqhb::cli
