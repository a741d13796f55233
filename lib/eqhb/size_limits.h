// Sizes refused before anything is allocated. Without these bounds a large
// harmonic count or sample count ends in std::bad_alloc, an abort inside
// FFTW, or an int overflow (k_max = 2H − 1, N ≥ 2 k_max + 1).
#pragma once

namespace eqhb {

// H: keeps 2 k_max + 1 = 4H − 1 far inside int.
inline constexpr int kMaxHarmonics = 1 << 20;
// N: samples per period of every channel.
inline constexpr int kMaxSamples = 1 << 24;

}  // namespace eqhb
