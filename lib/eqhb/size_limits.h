// Sizes refused before anything is allocated. Without these bounds a large
// harmonic count, sample count or DOF count ends in std::bad_alloc, an abort
// inside FFTW, or an int overflow (k_max = 2H − 1, N ≥ 2 k_max + 1).
#pragma once

#include <string>

namespace eqhb {

// H: keeps 2 k_max + 1 = 4H − 1 far inside int.
inline constexpr int kMaxHarmonics = 1 << 20;
// N: samples per period of every channel.
inline constexpr int kMaxSamples = 1 << 24;
// Memory one model may imply (its structure matrices, the coefficient and
// sample vectors, the law blocks, the factors and Jacobian of the system on
// the chosen linear-algebra path): 4 GiB.
inline constexpr double kMaxModelBytes = 4.0 * 1024 * 1024 * 1024;

// Bytes of a compressed sparse matrix of `columns` columns and `entries`
// stored entries (value and row index per entry, one offset per column).
inline double sparseBytes(double columns, double entries) { return 12.0 * entries + 4.0 * (columns + 1.0); }

// Throws InputError "FIELD = VALUE: WHAT needs about X GiB, more than the
// 4 GiB limit" when bytes > kMaxModelBytes.
void checkBytes(const std::string& field, const std::string& value, const std::string& what, double bytes);

}  // namespace eqhb
