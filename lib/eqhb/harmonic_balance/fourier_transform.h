// Time <-> frequency transforms of one channel on N equispaced samples
// t_i = iT/N, with FFTW plans made once per (basis, N) (spec §3).
//
//  synthesize: coefficients -> samples   x(t_i) = a0 + Σ a_k cos kθ_i + b_k sin kθ_i
//  project:    samples -> coefficients   the Galerkin projection with the
//              trapezoidal rule: a0 = (1/N) Σ y_i, a_k = (2/N) Σ y_i cos kθ_i,
//              b_k = (2/N) Σ y_i sin kθ_i; exact for trigonometric polynomials
//              of degree < N - H, so project(synthesize(c)) = c.
//  gram:       the weak-Jacobian block Q diag(d) P (Q the projection above, P
//              the basis samples), from ONE real FFT of d and the product
//              formulas cos·cos = ½[cos(k−j) + cos(k+j)] etc.: O(N log N + nb²)
//              instead of the O(N nb²) dense product.
//
// Half-wave sampling (opt-in, odd bases with even N): every channel of an
// odd basis is antiperiodic, q(t + T/2) = −q(t), so its first N/2 samples
// determine it. synthesize then writes, and project reads, only those
// M = N/2 samples (a complex FFT of size M with a twiddle e^{±iθ} folds the
// odd harmonics k = 2m + 1 onto the bins m, pruned to the bins the basis
// uses); gram reads M weights that must be
// half-period periodic (the even partials of an odd law), whose moments exist
// only at even orders. The results equal the full-period ones when the
// sampled functions have those symmetries; the law assembly uses it for laws
// that are odd (Law::oddSymmetric) and halves the work of a residual.
//
// All work buffers are owned; no call allocates. Not thread-safe (one
// instance per thread).
#pragma once

#include <Eigen/Dense>
#include <memory>

#include "eqhb/harmonic_balance/harmonic_set.h"

namespace eqhb {

// Coefficients of d/dt of the series with coefficients `in` at frequency ω:
// (a, b) of harmonic k -> (kω b, −kω a). A coefficient operation (no FFT);
// `in` and `out` must not alias.
void differentiateCoefficients(const HarmonicSet& basis, const double* in, double omega, double* out);

// One channel's series on `basis` at one instant, the fundamental's phase
// θ = ωt: its value and its derivative in θ (the rate is ω times it). A sum
// over the harmonics, where one instant is wanted and a transform would
// sample them all.
struct SeriesPoint {
  double value = 0.0, slope = 0.0;
};
SeriesPoint seriesAt(const HarmonicSet& basis, const double* coefficients, double theta);

enum class Sampling { kFullPeriod, kHalfWave };

class FourierTransform {
 public:
  // Throws InputError if samples < basis.minimumSamples(). kHalfWave is
  // honoured on an odd basis with an even sample count; otherwise the
  // transform samples the full period (halfWave() tells which).
  FourierTransform(const HarmonicSet& basis, int samples, Sampling sampling = Sampling::kFullPeriod);
  ~FourierTransform();
  FourierTransform(FourierTransform&&) noexcept;
  FourierTransform& operator=(FourierTransform&&) noexcept;
  FourierTransform(const FourierTransform&) = delete;
  FourierTransform& operator=(const FourierTransform&) = delete;

  const HarmonicSet& basis() const { return basis_; }
  int samples() const { return samples_; }
  bool halfWave() const { return half_wave_; }
  // Samples read and written per channel: N, or N/2 with half-wave sampling.
  int activeSamples() const { return half_wave_ ? samples_ / 2 : samples_; }

  void synthesize(const double* coefficients, double* samples);
  // Two channels at once: with half-wave sampling, one complex transform
  // for both (the real and imaginary parts); otherwise two synthesize calls.
  // The channels may differ by orders of magnitude (a velocity in m/s and a
  // force in N): the second is brought to the first's binary exponent before
  // the transform and back after it, both exact, so that the round-off of
  // the larger does not swamp the smaller and a change of units (a time
  // unit of 1/128 s) changes no bit of either.
  void synthesizePair(const double* first, const double* second, double* first_samples,
                      double* second_samples);
  void project(const double* samples, double* coefficients);
  // out (basis.size() x basis.size()) = Q diag(weights) P.
  void gram(const double* weights, Eigen::Ref<Eigen::MatrixXd> out);

  // differentiateCoefficients on this transform's basis.
  void differentiate(const double* in, double omega, double* out) const {
    differentiateCoefficients(basis_, in, omega, out);
  }
  // out = G Dω for a square block G (columns mixed per harmonic); used to
  // chain a weak-Jacobian block through the velocity. out must not alias g.
  void rightMultiplyDerivative(const Eigen::Ref<const Eigen::MatrixXd>& g, double omega,
                               Eigen::Ref<Eigen::MatrixXd> out) const;

 private:
  struct Plans;
  struct HalfWavePlans;
  HarmonicSet basis_;
  int samples_;
  bool half_wave_ = false;
  std::unique_ptr<Plans> plans_;  // real FFT of the active samples (gram; all of it on the full period)
  std::unique_ptr<HalfWavePlans> half_;
  std::unique_ptr<HalfWavePlans> pairs_;  // synthesizePair's, on twice the bins
};

}  // namespace eqhb
