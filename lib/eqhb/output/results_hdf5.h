// Curves and studies as HDF5 files beside their JSON and CSV (`eqhb sweep
// --hdf5`, `eqhb study --hdf5`): the same numbers as the JSON, as arrays.
//
// Sweep: attributes scene, solver, method, harmonics, samples, complete,
// stop_reason, peak_dof; datasets dof_labels [n], folds [f],
// points/{omega, energy, residual_norm, seconds} [m], points/{iterations,
// fold} [m], points/{max_abs, first_harmonic} [m x n] (the JSON's arrays per
// point), points/stable [m] (1, 0, −1 not analysed) with stability,
// points/error_estimate [m] (NaN where missing) with estimates,
// failed/{omega} [k], failed/termination [k].
// Study: attributes scene, mode, dof; datasets parameters [p] (the paths),
// samples/{sample} [s], samples/values [s x p], samples/status [s],
// samples/{peak_omega} [s] (NaN when failed), samples/{first_harmonic,
// max_abs} [s x n], samples/reason [s].
#pragma once

#include <string>

#include "eqhb/app/study.h"
#include "eqhb/app/sweep.h"

namespace eqhb::output {

// Throw IoError naming the file when it cannot be written.
void writeSweepHdf5(const std::string& path, const app::SweepResult& result);
void writeStudyHdf5(const std::string& path, const app::StudyRun& run);

}  // namespace eqhb::output
