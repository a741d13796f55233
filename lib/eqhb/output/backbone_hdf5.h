// A nonlinear mode's backbone as an HDF5 file beside its JSON (`eqhb modes
// --hdf5`): the numbers of `eqhb modes --json` (output/backbone_writers.h)
// as arrays, one row a point in the path's order.
//
// Attributes scene, solver, mode, from, to, complete (1/0), failed_points,
// seconds, linear_omega, linear_damping_ratio, and stop_why, stop_amplitude,
// stop_omega, stop_damping_ratio when the path stopped short. Datasets
// dof_labels [n], linear_shape [n], folds/{amplitude, omega, damping_ratio}
// [f], harmonics [h] (the harmonic numbers of the coefficients),
// points/{amplitude, seconds} [m], points/{converged, iterations} [m],
// points/termination [m], points/{omega, xi, damping_ratio,
// dissipated_energy} [m] and points/max_abs [m x n] (NaN where a point did
// not converge), points/{cos, sin} [m x n x h] (each DOF's Fourier
// coefficients, the JSON's channels.dofs[i].coefficients; NaN likewise).
#pragma once

#include <string>

#include "eqhb/app/modes.h"

namespace eqhb::output {

// Throws IoError naming the file when it cannot be written.
void writeBackboneHdf5(const std::string& path, const app::ModesRun& run);

}  // namespace eqhb::output
