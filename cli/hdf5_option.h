// --hdf5 FILE of the commands that write curves, studies or backbones: the option, and
// the writers of output/results_hdf5.h when the command was built with HDF5
// (EQHB_WITH_HDF5), else an error saying so.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "eqhb/app/modes.h"
#include "eqhb/app/study.h"
#include "eqhb/app/sweep.h"

namespace eqhb::cli {

void addHdf5Option(CLI::App* command, std::string& path, const std::string& what);
// Throw IoError when the file cannot be written, std::runtime_error when
// this build has no HDF5.
void writeSweepHdf5File(const std::string& path, const app::SweepResult& result);
void writeStudyHdf5File(const std::string& path, const app::StudyRun& run);
void writeBackboneHdf5File(const std::string& path, const app::ModesRun& run);

}  // namespace eqhb::cli
