#include "eqhb/harmonic_balance/fourier_transform.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/size_limits.h"

namespace eqhb {

namespace {
// FFTW's planner (plan creation and destruction) is not thread-safe; the
// transforms themselves are. Studies build systems on several threads.
std::mutex& plannerMutex() {
  static std::mutex mutex;
  return mutex;
}
}  // namespace

struct FourierTransform::Plans {
  int n = 0;
  double* real = nullptr;          // N samples
  fftw_complex* spectrum = nullptr;  // N/2 + 1 bins
  fftw_plan forward = nullptr;     // real -> spectrum
  fftw_plan backward = nullptr;    // spectrum -> real (destroys spectrum); none with half-wave sampling

  Plans(int samples, bool with_backward) : n(samples) {
    real = fftw_alloc_real(n);
    spectrum = fftw_alloc_complex(n / 2 + 1);
    const std::lock_guard<std::mutex> lock(plannerMutex());
    forward = fftw_plan_dft_r2c_1d(n, real, spectrum, FFTW_ESTIMATE);
    if (with_backward) backward = fftw_plan_dft_c2r_1d(n, spectrum, real, FFTW_ESTIMATE);
  }
  ~Plans() {
    const std::lock_guard<std::mutex> lock(plannerMutex());
    fftw_destroy_plan(forward);
    if (backward != nullptr) fftw_destroy_plan(backward);
    fftw_free(real);
    fftw_free(spectrum);
  }
  // Σ_i y_i cos(mθ_i) / N and Σ_i y_i sin(mθ_i) / N for any m >= 0, from the
  // half spectrum of the last forward transform (X_m = Σ y e^{-imθ}).
  void cosSinMoment(int m, double* c, double* s) const {
    m %= n;
    double sign = 1.0;
    if (m > n / 2) {  // X_{N-m} = conj(X_m) for real input
      m = n - m;
      sign = -1.0;
    }
    *c = spectrum[m][0] / n;
    *s = -sign * spectrum[m][1] / n;
  }
};

// Odd harmonics on the first half period (θ_i = 2πi/N, i < M = N/2): with
// k = 2m + 1, x_i = Re Σ_m C_m e^{ikθ_i}, C_m = a_k − ib_k, only m < L
// non-zero, L the least divisor of M above the highest m. Splitting
// i = p + Pq (P = M/L, p < P, q < L) gives e^{ikθ_i} = T_pm e^{iπq/L}
// e^{2πi·mq/L} with T_pm = e^{ikθ_p}, so the synthesis is P transforms of
// size L of C_m T_pm, each output twisted by e^{iπq/L}: the full transform
// of size M pruned to its non-zero bins (L = 16, P = 32 instead of 512 for
// H = 10, N = 1024). The projection, (4/N) Σ_{i<M} y_i e^{−ikθ_i} (the
// second half repeats the first for antiperiodic y and odd k), is the same
// backwards: P transforms of y_i e^{−iπq/L} over q, summed against conj T_pm.
// The transforms read and write i = p + Pq in place through their strides.
//
// Two channels at once (synthesizePair): x¹ + ix² = ½ Σ_m [(C¹_m + iC²_m)
// e^{ikθ} + (conj C¹_m + i conj C²_m) e^{−ikθ}], and −k = 2(−m − 1) + 1 puts
// the second terms on the bins L − 1 − m: one complex transform for two
// real channels, with L at least twice the basis' bins.
struct FourierTransform::HalfWavePlans {
  int m = 0, length = 0, batches = 0;                 // M, L, P
  std::vector<double> twist_cos, twist_sin;           // e^{iπq/L} at sample i = p + Pq
  std::vector<double> inner_cos, inner_sin;           // T_pm at [m * P + p], m < L
  fftw_complex* bins = nullptr;     // synthesis input C_m T_pm at [p * L + m]: zero but at the basis' bins
  fftw_complex* samples = nullptr;  // synthesis output, projection input y_i e^{−iπq/L}, at i
  fftw_complex* moments = nullptr;  // projection output at [p * L + m] (projection plans only)
  fftw_plan backward = nullptr;     // bins -> samples (input preserved)
  fftw_plan forward = nullptr;      // samples -> moments (projection plans only)

  // L is the least divisor of M that is >= least_length.
  HalfWavePlans(int samples_per_period, int least_length, bool with_projection)
      : m(samples_per_period / 2), length(leastDivisorFrom(m, least_length)), batches(m / length),
        twist_cos(m), twist_sin(m), inner_cos(static_cast<size_t>(length) * batches),
        inner_sin(inner_cos.size()) {
    for (int i = 0; i < m; ++i) {
      const double phase = M_PI * (i / batches) / length;
      twist_cos[i] = std::cos(phase);
      twist_sin[i] = std::sin(phase);
    }
    for (int b = 0; b < length; ++b)
      for (int p = 0; p < batches; ++p) {
        const double theta = 2.0 * M_PI * (2 * b + 1) * p / samples_per_period;
        inner_cos[b * batches + p] = std::cos(theta);
        inner_sin[b * batches + p] = std::sin(theta);
      }
    bins = fftw_alloc_complex(m);
    samples = fftw_alloc_complex(m);
    if (with_projection) moments = fftw_alloc_complex(m);
    std::memset(bins, 0, sizeof(fftw_complex) * m);
    const std::lock_guard<std::mutex> lock(plannerMutex());
    const int n[] = {length};
    backward = fftw_plan_many_dft(1, n, batches, bins, nullptr, 1, length, samples, nullptr, batches, 1,
                                  FFTW_BACKWARD, FFTW_ESTIMATE | FFTW_PRESERVE_INPUT);
    if (with_projection)
      forward = fftw_plan_many_dft(1, n, batches, samples, nullptr, batches, 1, moments, nullptr, 1, length,
                                   FFTW_FORWARD, FFTW_ESTIMATE);
  }
  ~HalfWavePlans() {
    const std::lock_guard<std::mutex> lock(plannerMutex());
    fftw_destroy_plan(backward);
    if (forward != nullptr) fftw_destroy_plan(forward);
    fftw_free(bins);
    fftw_free(samples);
    fftw_free(moments);
  }
  // The least divisor of m that is >= least (m itself at worst).
  static int leastDivisorFrom(int m, int least) {
    for (int l = least; l < m; ++l)
      if (m % l == 0) return l;
    return m;
  }
};

FourierTransform::FourierTransform(const HarmonicSet& basis, int samples, Sampling sampling)
    : basis_(basis), samples_(samples) {
  if (samples < basis.minimumSamples())
    throwInputError("samples", std::to_string(samples),
                    "must be >= 2 k_max + 1 = " + std::to_string(basis.minimumSamples()) +
                        " to resolve the highest harmonic k_max = " + std::to_string(basis.highest()));
  if (samples > kMaxSamples)
    throwInputError("samples", std::to_string(samples), "must be <= " + std::to_string(kMaxSamples));
  half_wave_ = sampling == Sampling::kHalfWave && basis.kind() == HarmonicKind::kOdd && samples % 2 == 0;
  plans_ = std::make_unique<Plans>(activeSamples(), !half_wave_);  // half-wave synthesis has its own plan
  if (half_wave_) {
    const int bins = (basis.highest() + 1) / 2;  // m = 0 .. (k_max − 1)/2
    half_ = std::make_unique<HalfWavePlans>(samples, bins, true);
    pairs_ = std::make_unique<HalfWavePlans>(samples, 2 * bins, false);  // M >= k_max + 1 = 2 bins
  }
}

FourierTransform::~FourierTransform() = default;
FourierTransform::FourierTransform(FourierTransform&&) noexcept = default;
FourierTransform& FourierTransform::operator=(FourierTransform&&) noexcept = default;

void FourierTransform::synthesize(const double* coefficients, double* samples) {
  const auto& ks = basis_.harmonics();
  if (half_wave_) {
    HalfWavePlans& w = *half_;
    for (size_t h = 0; h < ks.size(); ++h) {
      const double* c = coefficients + basis_.offset(static_cast<int>(h));
      const int m = (ks[h] - 1) / 2;
      const double* tc = w.inner_cos.data() + static_cast<size_t>(m) * w.batches;
      const double* ts = w.inner_sin.data() + static_cast<size_t>(m) * w.batches;
      for (int p = 0; p < w.batches; ++p) {  // (a − ib) T_pm
        w.bins[p * w.length + m][0] = c[0] * tc[p] + c[1] * ts[p];
        w.bins[p * w.length + m][1] = c[0] * ts[p] - c[1] * tc[p];
      }
    }
    fftw_execute(w.backward);
    for (int i = 0; i < w.m; ++i)
      samples[i] = w.twist_cos[i] * w.samples[i][0] - w.twist_sin[i] * w.samples[i][1];
    return;
  }
  Plans& p = *plans_;
  std::memset(p.spectrum, 0, sizeof(fftw_complex) * (p.n / 2 + 1));
  for (size_t h = 0; h < ks.size(); ++h) {
    const int k = ks[h];
    const double* c = coefficients + basis_.offset(static_cast<int>(h));
    if (k == 0) {
      p.spectrum[0][0] = c[0];
    } else {  // a cos + b sin = Re((a − ib) e^{ikθ}); c2r doubles bins 0 < k < N/2
      p.spectrum[k][0] = 0.5 * c[0];
      p.spectrum[k][1] = -0.5 * c[1];
    }
  }
  fftw_execute(p.backward);
  std::memcpy(samples, p.real, sizeof(double) * p.n);
}

namespace {
// |s| up to this keeps 2^s and 2^−s normal doubles (exponents −1022..1023).
constexpr int kLargestPowerShift = 1000;

// 2^e with e the difference of the binary exponents of the largest
// coefficients of `first` and `second` (0 when either is all zero): the
// factor that brings the second channel to the first's magnitude exactly.
int balancingExponent(const double* first, const double* second, int count) {
  double most_first = 0.0, most_second = 0.0;
  for (int i = 0; i < count; ++i) {
    most_first = std::max(most_first, std::abs(first[i]));
    most_second = std::max(most_second, std::abs(second[i]));
  }
  if (!(most_first > 0.0) || !(most_second > 0.0) || !std::isfinite(most_first) || !std::isfinite(most_second))
    return 0;
  int e_first = 0, e_second = 0;
  std::frexp(most_first, &e_first);
  std::frexp(most_second, &e_second);
  return e_first - e_second;
}
}  // namespace

void FourierTransform::synthesizePair(const double* first, const double* second, double* first_samples,
                                      double* second_samples) {
  if (!half_wave_) {
    synthesize(first, first_samples);
    synthesize(second, second_samples);
    return;
  }
  const auto& ks = basis_.harmonics();
  HalfWavePlans& w = *pairs_;
  const int shift = balancingExponent(first, second, basis_.size());
  // x · 2^s is rounded once, as ldexp(x, s) is: the same double, without a
  // library call per sample, wherever 2^±s is itself a double.
  const bool exact = std::abs(shift) <= kLargestPowerShift;
  const double up = exact ? std::ldexp(1.0, shift) : 0.0, down = exact ? std::ldexp(1.0, -shift) : 0.0;
  auto scaleUp = [&](double x) { return exact ? x * up : std::ldexp(x, shift); };
  for (size_t h = 0; h < ks.size(); ++h) {
    const int o = basis_.offset(static_cast<int>(h));
    const double a1 = first[o], b1 = first[o + 1];
    const double a2 = scaleUp(second[o]), b2 = scaleUp(second[o + 1]);
    // ½(C¹ + iC²) and ½(conj C¹ + i conj C²), C = a − ib
    const double ur = 0.5 * (a1 + b2), ui = 0.5 * (a2 - b1);
    const double vr = 0.5 * (a1 - b2), vi = 0.5 * (a2 + b1);
    const int m = (ks[h] - 1) / 2, mirror = w.length - 1 - m;
    const double* tc = w.inner_cos.data() + static_cast<size_t>(m) * w.batches;
    const double* ts = w.inner_sin.data() + static_cast<size_t>(m) * w.batches;
    for (int p = 0; p < w.batches; ++p) {  // U T_pm and V conj T_pm
      w.bins[p * w.length + m][0] = ur * tc[p] - ui * ts[p];
      w.bins[p * w.length + m][1] = ur * ts[p] + ui * tc[p];
      w.bins[p * w.length + mirror][0] = vr * tc[p] + vi * ts[p];
      w.bins[p * w.length + mirror][1] = vi * tc[p] - vr * ts[p];
    }
  }
  fftw_execute(w.backward);
  if (exact) {
    for (int i = 0; i < w.m; ++i) {
      const double re = w.samples[i][0], im = w.samples[i][1];
      first_samples[i] = w.twist_cos[i] * re - w.twist_sin[i] * im;
      second_samples[i] = (w.twist_cos[i] * im + w.twist_sin[i] * re) * down;
    }
    return;
  }
  for (int i = 0; i < w.m; ++i) {
    const double re = w.samples[i][0], im = w.samples[i][1];
    first_samples[i] = w.twist_cos[i] * re - w.twist_sin[i] * im;
    second_samples[i] = std::ldexp(w.twist_cos[i] * im + w.twist_sin[i] * re, -shift);
  }
}

void FourierTransform::project(const double* samples, double* coefficients) {
  const auto& ks = basis_.harmonics();
  if (half_wave_) {
    HalfWavePlans& w = *half_;
    for (int i = 0; i < w.m; ++i) {
      w.samples[i][0] = samples[i] * w.twist_cos[i];
      w.samples[i][1] = -samples[i] * w.twist_sin[i];
    }
    fftw_execute(w.forward);
    const double scale = 2.0 / w.m;  // 4/N
    for (size_t h = 0; h < ks.size(); ++h) {
      double* c = coefficients + basis_.offset(static_cast<int>(h));
      const int m = (ks[h] - 1) / 2;
      const double* tc = w.inner_cos.data() + static_cast<size_t>(m) * w.batches;
      const double* ts = w.inner_sin.data() + static_cast<size_t>(m) * w.batches;
      double re = 0.0, im = 0.0;  // Σ_p conj(T_pm) G_pm
      for (int p = 0; p < w.batches; ++p) {
        const double gr = w.moments[p * w.length + m][0], gi = w.moments[p * w.length + m][1];
        re += tc[p] * gr + ts[p] * gi;
        im += tc[p] * gi - ts[p] * gr;
      }
      c[0] = scale * re;
      c[1] = -scale * im;
    }
    return;
  }
  Plans& p = *plans_;
  std::memcpy(p.real, samples, sizeof(double) * p.n);
  fftw_execute(p.forward);
  for (size_t h = 0; h < ks.size(); ++h) {
    const int k = ks[h];
    double* c = coefficients + basis_.offset(static_cast<int>(h));
    double cm, sm;
    p.cosSinMoment(k, &cm, &sm);
    if (k == 0) {
      c[0] = cm;
    } else {
      c[0] = 2.0 * cm;
      c[1] = 2.0 * sm;
    }
  }
}

void FourierTransform::gram(const double* weights, Eigen::Ref<Eigen::MatrixXd> out) {
  Plans& p = *plans_;
  std::memcpy(p.real, weights, sizeof(double) * p.n);
  fftw_execute(p.forward);
  const auto& ks = basis_.harmonics();
  const int count = static_cast<int>(ks.size());
  // Moments (1/N) Σ_{i<N} d_i (cos, sin)(mθ_i). Half-wave: d has period T/2,
  // so they vanish at odd m and are (1/M) Σ_{i<M} d_i e^{−i(m/2)·2πi/M} at
  // even m: the size-M transform at bin m/2 (odd bases meet only even k ± j).
  const bool half = half_wave_;
  auto moment = [&p, half](int m, double* c, double* s) {
    if (!half) return p.cosSinMoment(m, c, s);
    if (m % 2 != 0) {
      *c = *s = 0.0;
      return;
    }
    p.cosSinMoment(m / 2, c, s);
  };
  // Row k of Q carries 2/N (1/N for k = 0); C_m, S_m below carry 1/N.
  for (int hr = 0; hr < count; ++hr) {
    const int k = ks[hr];
    const int row = basis_.offset(hr);
    const double rowScale = k == 0 ? 1.0 : 2.0;
    for (int hc = 0; hc < count; ++hc) {
      const int j = ks[hc];
      const int col = basis_.offset(hc);
      double cDiff, sDiff, cSum, sSum;  // moments at |k − j| and k + j
      moment(k >= j ? k - j : j - k, &cDiff, &sDiff);
      if (k < j) sDiff = -sDiff;  // S_{k−j} is odd in k − j
      moment(k + j, &cSum, &sSum);
      if (k == 0 && j == 0) {
        out(row, col) = cDiff;
        continue;
      }
      if (j == 0) {  // φ_j = 1
        out(row, col) = rowScale * cDiff;
        out(row + 1, col) = rowScale * sDiff;
        continue;
      }
      if (k == 0) {
        out(row, col) = cSum;      // mean of d cos jθ: C_j
        out(row, col + 1) = sSum;  // mean of d sin jθ: S_j
        continue;
      }
      const double h = 0.5 * rowScale;
      out(row, col) = h * (cDiff + cSum);          // cos k · cos j
      out(row, col + 1) = h * (sSum - sDiff);      // cos k · sin j
      out(row + 1, col) = h * (sSum + sDiff);      // sin k · cos j
      out(row + 1, col + 1) = h * (cDiff - cSum);  // sin k · sin j
    }
  }
}

void differentiateCoefficients(const HarmonicSet& basis, const double* in, double omega, double* out) {
  const auto& ks = basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int k = ks[h];
    const int o = basis.offset(static_cast<int>(h));
    if (k == 0) {
      out[o] = 0.0;
    } else {
      const double kw = k * omega;
      out[o] = kw * in[o + 1];
      out[o + 1] = -kw * in[o];
    }
  }
}

SeriesPoint seriesAt(const HarmonicSet& basis, const double* c, double theta) {
  SeriesPoint out;
  const auto& ks = basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int k = ks[h], o = basis.offset(static_cast<int>(h));
    if (k == 0) {
      out.value += c[o];
      continue;
    }
    const double cosine = std::cos(k * theta), sine = std::sin(k * theta);
    out.value += c[o] * cosine + c[o + 1] * sine;
    out.slope += k * (c[o + 1] * cosine - c[o] * sine);
  }
  return out;
}

void FourierTransform::rightMultiplyDerivative(const Eigen::Ref<const Eigen::MatrixXd>& g,
                                               double omega,
                                               Eigen::Ref<Eigen::MatrixXd> out) const {
  // Dω maps (a, b) -> (kω b, −kω a): column cos_k of G Dω is −kω G(:, sin_k),
  // column sin_k is kω G(:, cos_k).
  const auto& ks = basis_.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int k = ks[h];
    const int o = basis_.offset(static_cast<int>(h));
    if (k == 0) {
      out.col(o).setZero();
    } else {
      const double kw = k * omega;
      out.col(o) = -kw * g.col(o + 1);
      out.col(o + 1) = kw * g.col(o);
    }
  }
}

}  // namespace eqhb
