#include "eqhb/accuracy/error_estimate.h"

#include <algorithm>
#include <cmath>

#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

namespace {

// x_i(t) of one channel's coefficients (HarmonicSet layout).
double seriesValue(const HarmonicSet& basis, const double* c, double omega, double t) {
  double x = 0.0;
  for (size_t h = 0; h < basis.harmonics().size(); ++h) {
    const int k = basis.harmonics()[h], o = basis.offset(static_cast<int>(h));
    x += k == 0 ? c[o] : c[o] * std::cos(k * omega * t) + c[o + 1] * std::sin(k * omega * t);
  }
  return x;
}

}  // namespace

HbModel withHarmonics(const HbModel& model, int harmonics) {
  HbModel out = model;
  out.basis = HarmonicSet(model.basis.kind(), harmonics);
  const double ratio = static_cast<double>(out.basis.highest()) / std::max(1, model.basis.highest());
  int samples = static_cast<int>(std::ceil(model.samples * ratio));
  samples += samples % 2;
  out.samples = std::max(samples, out.basis.minimumSamples());
  return out;
}

Eigen::VectorXd peakDisplacements(const HbModel& model, const Eigen::VectorXd& full) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  int count = 64;
  while (count < 16 * model.basis.highest()) count *= 2;
  FourierTransform transform(model.basis, count);
  Eigen::VectorXd samples(count), peaks(n);
  const double period = 2.0 * M_PI / model.omega, dt = period / count;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < n; ++i) {
    const double* c = full.data() + i * nb;
    transform.synthesize(c, samples.data());
    Eigen::Index best = 0;
    samples.cwiseAbs().maxCoeff(&best);
    auto value = [&](double t) { return std::abs(seriesValue(model.basis, c, model.omega, t)); };
    // |x| is unimodal within one sample of its best sample at this resolution.
    double a = best * dt - dt, b = best * dt + dt;
    for (int it = 0; it < 60; ++it) {
      const double p = b - golden * (b - a), q = a + golden * (b - a);
      if (value(p) > value(q)) b = q;
      else a = p;
    }
    peaks[i] = std::max(std::abs(samples[best]), value(0.5 * (a + b)));
  }
  return peaks;
}

double worstRelativeDifference(const Eigen::VectorXd& value, const Eigen::VectorXd& reference) {
  const double floor = kRestFloor * reference.cwiseAbs().maxCoeff();
  double worst = 0.0;
  for (Eigen::Index i = 0; i < value.size(); ++i) {
    const double scale = std::max(std::abs(reference[i]), floor);
    if (scale > 0.0) worst = std::max(worst, std::abs(value[i] - reference[i]) / scale);
  }
  return worst;
}

ErrorEstimate compareWithRefined(const HbModel& model, const Eigen::VectorXd& full, const HbModel& refined_model,
                                 const Eigen::VectorXd& refined_full) {
  ErrorEstimate e;
  e.available = true;
  e.refined_harmonics = refined_model.basis.count();
  e.refined_samples = refined_model.samples;
  e.refined_full = refined_full;
  e.max_abs_difference =
      worstRelativeDifference(peakDisplacements(model, full), peakDisplacements(refined_model, refined_full));
  e.max_abs = e.factor * e.max_abs_difference;
  // Displacement coefficients only: the forces of set-valued laws converge
  // in a weaker norm and max|x| is what is asked.
  const int displacement_size = model.structure.dofs() * refined_model.basis.size();
  const Eigen::VectorXd padded = transferCoefficients(model, refined_model, full);
  const double norm = refined_full.head(displacement_size).norm();
  if (norm > 0.0)
    e.coefficients =
        e.factor * (padded.head(displacement_size) - refined_full.head(displacement_size)).norm() / norm;
  return e;
}

ErrorEstimate estimateError(const HbModel& model, const Eigen::VectorXd& full, Solver& solver,
                            const SolverOptions& options, bool condensed, const FallbackChain* fallbacks) {
  const HbModel refined_model = withHarmonics(model, 2 * model.basis.count());
  auto system = makeHbSystem(refined_model, condensed, options.linear_algebra);
  const Eigen::VectorXd z0 = system->fromFullCoefficients(transferCoefficients(model, refined_model, full));
  SolverResult refined = solver.solve(*system, z0, options);
  FallbackReport report;
  if (!refined.converged() && fallbacks && !fallbacks->steps.empty()) {
    const double first_seconds = refined.seconds;
    refined = solveWithFallbacks(*system, solver, options, refined, false, *fallbacks, &report);
    refined.seconds = first_seconds + report.seconds;  // the failed solve and every step
  }
  ErrorEstimate e = compareWithRefined(model, full, refined_model, system->fullCoefficients(refined.solution));
  e.available = refined.converged();
  e.refined = refined;
  e.fallback = report.taken;
  return e;
}

}  // namespace eqhb
