#include "eqhb/references/time_integrator.h"

#include <chrono>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/references/theta_step.h"

namespace eqhb {

void TimeOptions::validate() const {
  if (!(step > 0.0) || !std::isfinite(step)) throwInputError("step", formatNumber(step), "must be finite and > 0");
  if (!(theta >= 0.5 && theta <= 1.0)) throwInputError("theta", formatNumber(theta), "must be in [0.5, 1]");
  if (max_periods < 1) throwInputError("periods", std::to_string(max_periods), "must be >= 1");
  if (!(periodic_tolerance > 0.0)) throwInputError("periodic tolerance", formatNumber(periodic_tolerance), "must be > 0");
  if (!(restitution >= 0.0 && restitution <= 1.0))
    throwInputError("restitution", formatNumber(restitution), "must be in [0, 1]");
  if (!(max_seconds >= 0.0) || !std::isfinite(max_seconds))
    throwInputError("max seconds", formatNumber(max_seconds), "must be finite and >= 0 (0: no limit)");
}

namespace {

double periodOf(const HbModel& model) { return 2.0 * M_PI / model.omega; }

// Steps per period T of about options.step each, bounded by kMaxStepsPerPeriod.
int stepsPerPeriod(const HbModel& model, const TimeOptions& options) {
  const double period = periodOf(model);
  const double wanted = std::ceil(period / options.step);  // checked before it becomes an int
  if (wanted > kMaxStepsPerPeriod)
    throwInputError("step", formatNumber(options.step),
                    "gives " + formatNumber(wanted) + " steps per period T = " + formatNumber(period) +
                        ", more than " + formatNumber(kMaxStepsPerPeriod));
  return std::max(1, static_cast<int>(wanted));
}

// The record of one period: `steps` samples of x, v and the laws' forces.
TimeReference emptyReference(const HbModel& model, int steps, double h) {
  TimeReference ref;
  ref.step = h;
  ref.steps_per_period = steps;
  ref.displacement.resize(steps, model.structure.dofs());
  ref.velocity.resize(steps, model.structure.dofs());
  ref.force.resize(steps, model.lawComponents());
  return ref;
}

// Sample (k + 1) mod steps is t = (k + 1) h: the period recorded last
// overwrites the ones before.
void recordSample(int sample, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                  const std::vector<LocalVector>& lambda, TimeReference* ref) {
  ref->displacement.row(sample) = x.transpose();
  ref->velocity.row(sample) = v.transpose();
  int q = 0;
  for (const LocalVector& force : lambda)
    for (int a = 0; a < force.size(); ++a, ++q) ref->force(sample, q) = force[a];
}

// How far the state moved over the period, relative to the period's largest
// displacement and velocity.
double periodicityError(const TimeReference& ref, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                        const Eigen::VectorXd& x_start, const Eigen::VectorXd& v_start) {
  const double scale = std::max({ref.displacement.cwiseAbs().maxCoeff(), ref.velocity.cwiseAbs().maxCoeff(), 1e-300});
  return std::max((x - x_start).cwiseAbs().maxCoeff(), (v - v_start).cwiseAbs().maxCoeff()) / scale;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The Fourier coefficients of the last period recorded on the model's basis,
// DOFs then law components.
void projectLastPeriod(const HbModel& model, TimeReference* ref) {
  const int steps = ref->steps_per_period, n = model.structure.dofs(), components = model.lawComponents();
  const int nb = model.basis.size();
  FourierTransform transform(model.basis, steps);
  ref->coefficients.setZero((n + components) * nb);
  Eigen::VectorXd column(steps);
  for (int i = 0; i < n; ++i) {
    column = ref->displacement.col(i);
    transform.project(column.data(), ref->coefficients.data() + i * nb);
  }
  for (int q = 0; q < components; ++q) {
    column = ref->force.col(q);
    transform.project(column.data(), ref->coefficients.data() + (n + q) * nb);
  }
}

}  // namespace

TimeReference integrateToSteadyState(const HbModel& model, const TimeOptions& options,
                                     const Eigen::VectorXd& initial_full, const PeriodCallback& on_period) {
  model.validate();
  options.validate();
  const auto start_clock = std::chrono::steady_clock::now();
  const int n = model.structure.dofs();
  const int steps = stepsPerPeriod(model, options);
  const double h = periodOf(model) / steps;
  ThetaStep step(model, options, h);

  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), v = Eigen::VectorXd::Zero(n);
  const int nb = model.basis.size();
  if (initial_full.size() > 0)
    for (int i = 0; i < n; ++i) {  // the series' state at t = 0
      const SeriesPoint at = seriesAt(model.basis, initial_full.data() + i * nb, 0.0);
      x[i] = at.value;
      v[i] = model.omega * at.slope;
    }
  std::vector<LocalVector> lambda;
  for (const auto& attached : model.laws) lambda.push_back(LocalVector::Zero(attached.law->dimension()));
  TimeReference ref = emptyReference(model, steps, h);

  // Period after period until the state repeats (periodic), diverges, or the
  // time allowed runs out.
  for (int p = 0; p < options.max_periods; ++p) {
    const Eigen::VectorXd x_period_start = x, v_period_start = v;
    for (int k = 0; k < steps; ++k) {
      step.advance((static_cast<double>(p) * steps + k) * h, x, v, lambda);
      recordSample((k + 1) % steps, x, v, lambda, &ref);
    }
    ref.periods = p + 1;
    ref.periodicity_error = periodicityError(ref, x, v, x_period_start, v_period_start);
    if (on_period) on_period(ref.periods, ref.periodicity_error);
    const bool diverged = !std::isfinite(ref.periodicity_error);
    if (diverged) break;
    ref.periodic = p > 0 && ref.periodicity_error <= options.periodic_tolerance;
    if (ref.periodic) break;
    ref.timed_out = options.max_seconds > 0.0 && secondsSince(start_clock) >= options.max_seconds;
    if (ref.timed_out) break;
  }
  projectLastPeriod(model, &ref);
  ref.seconds = secondsSince(start_clock);
  return ref;
}

std::vector<ChannelError> compareWithReference(const HbModel& model, const Eigen::VectorXd& hb_full,
                                               const TimeReference& reference) {
  const int steps = reference.steps_per_period;
  FourierTransform transform(model.basis, steps);
  const int nb = model.basis.size(), n = model.structure.dofs(), components = model.lawComponents();
  // Each kind's floor: a channel that barely moves (a blocked normal DOF, a
  // force that stays near zero) is measured against 1e-3 of the largest
  // channel of its kind, so that rounding noise over a vanishing reference
  // does not read as a relative error of order one (or 1e300).
  auto floor_of = [](const Eigen::MatrixXd& m) {
    double largest = 0.0;
    for (int c = 0; c < m.cols(); ++c) largest = std::max(largest, m.col(c).norm());
    return std::max(kChannelFloor * largest, 1e-300);
  };
  auto amplitude_floor = [&](int first, int count) {
    double largest = 0.0;
    for (int c = first; c < first + count; ++c)
      largest = std::max(largest, firstHarmonicAmplitude(model.basis, reference.coefficients.data() + c * nb));
    return std::max(kChannelFloor * largest, 1e-300);
  };
  const double x_floor = floor_of(reference.displacement), v_floor = floor_of(reference.velocity),
               f_floor = components > 0 ? floor_of(reference.force) : 1e-300;
  const double x_peak_floor = kChannelFloor * reference.displacement.cwiseAbs().maxCoeff(),
               f_peak_floor = components > 0 ? kChannelFloor * reference.force.cwiseAbs().maxCoeff() : 0.0;
  const double x_amplitude_floor = amplitude_floor(0, n), f_amplitude_floor = amplitude_floor(n, components);
  Eigen::VectorXd hb(steps), rate_coefficients(nb);
  auto fill = [&](ChannelError& e, const Eigen::VectorXd& ref, const double* hb_c, const double* ref_c, double floor,
                  double peak_floor, double amplitude_floor) {
    transform.synthesize(hb_c, hb.data());
    e.relative_l2 = (hb - ref).norm() / std::max(ref.norm(), floor);
    e.max_abs_reference = ref.cwiseAbs().maxCoeff();
    e.max_abs_hb = hb.cwiseAbs().maxCoeff();
    e.relative_max_abs =
        std::abs(e.max_abs_hb - e.max_abs_reference) / std::max({e.max_abs_reference, peak_floor, 1e-300});
    const double a_ref = firstHarmonicAmplitude(model.basis, ref_c);
    e.first_harmonic_error =
        std::abs(firstHarmonicAmplitude(model.basis, hb_c) - a_ref) / std::max(a_ref, amplitude_floor);
  };
  std::vector<ChannelError> errors;
  for (int i = 0; i < n; ++i) {
    ChannelError e;
    e.label = dofLabel(i);
    fill(e, reference.displacement.col(i), hb_full.data() + i * nb, reference.coefficients.data() + i * nb, x_floor,
         x_peak_floor, x_amplitude_floor);
    transform.differentiate(hb_full.data() + i * nb, model.omega, rate_coefficients.data());
    transform.synthesize(rate_coefficients.data(), hb.data());
    const Eigen::VectorXd ref_rate = reference.velocity.col(i);
    e.relative_l2_rate = (hb - ref_rate).norm() / std::max(ref_rate.norm(), v_floor);
    errors.push_back(e);
  }
  const std::vector<std::string> labels = lawComponentLabels(model);
  for (int q = 0; q < components; ++q) {
    ChannelError e;
    e.label = labels[q];
    fill(e, reference.force.col(q), hb_full.data() + (n + q) * nb, reference.coefficients.data() + (n + q) * nb,
         f_floor, f_peak_floor, f_amplitude_floor);
    errors.push_back(e);
  }
  return errors;
}

}  // namespace eqhb
