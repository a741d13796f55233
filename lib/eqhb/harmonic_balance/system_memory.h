// Bytes a model's harmonic-balance systems will hold, estimated from the
// sizes alone, so that a model too large for memory is refused (InputError,
// kMaxModelBytes in size_limits.h) before anything is allocated. The bound
// follows the linear-algebra path: dense matrices are counted only where the
// path stores them densely, sparse ones by their entries.
#pragma once

#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

// The sizes modelBytes depends on, known before a structure is built: a
// scene checks them before it allocates the structure (or reads its files).
struct ModelSizes {
  double dofs = 0.0;
  double structure_entries = 0.0;  // stored entries of M, C and K together
  double coefficients = 0.0;       // nb
  double samples = 0.0;            // N
  std::vector<int> law_dimensions;
};
ModelSizes modelSizes(const HbModel& model);

// What every system of the model holds, on any path: the sparse M, C and K,
// the coefficient vectors of every channel, and per law its samples, its
// nb x nb Jacobian blocks (2 d² of them) and the FFT scratch.
double modelBytes(const ModelSizes& sizes);
double modelBytes(const HbModel& model);
// modelBytes plus the condensed system: the factors of every A_k (dense
// (w n)² per harmonic, or sparse: the entries of A_k, a lower bound of the
// factors' fill-in), the receptance at the law DOFs and the dense Jacobian
// of the q nb unknowns with the solvers' copies of it.
double condensedBytes(const HbModel& model, bool sparse_factors);
// modelBytes plus the full system: its sparse Jacobian (per harmonic the
// w x w blocks of A_k on the pattern of M, C and K; the law rows' nb x nb
// blocks), the set-up triplets and the solvers' copies.
double fullBytes(const HbModel& model);

// "(n DOFs, q law components, nb coefficients and N samples per channel)".
std::string describeSizes(const HbModel& model);

}  // namespace eqhb
