#include "eqhb/references/time_integrator.h"

#include <chrono>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_solution.h"

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

// State of a Fourier series [x coefficients] at t = 0 and its rate.
void stateAtZero(const HarmonicSet& basis, const double* c, double omega, double* x, double* v) {
  *x = 0.0;
  *v = 0.0;
  for (size_t h = 0; h < basis.harmonics().size(); ++h) {
    const int k = basis.harmonics()[h], o = basis.offset(static_cast<int>(h));
    *x += c[o];                      // cos(0) = 1
    if (k > 0) *v += k * omega * c[o + 1];  // d/dt b sin(kωt) at 0
  }
}

}  // namespace

TimeReference integrateToSteadyState(const HbModel& model, const TimeOptions& options,
                                     const Eigen::VectorXd& initial_full, const PeriodCallback& on_period) {
  model.validate();
  options.validate();
  const auto start_clock = std::chrono::steady_clock::now();
  const LinearStructure& s = model.structure;
  const int n = s.dofs();
  const double period = 2.0 * M_PI / model.omega;
  const double wanted = std::ceil(period / options.step);  // checked before it becomes an int
  if (wanted > kMaxStepsPerPeriod)
    throwInputError("step", formatNumber(options.step),
                    "gives " + formatNumber(wanted) + " steps per period T = " + formatNumber(period) +
                        ", more than " + formatNumber(kMaxStepsPerPeriod));
  const int steps = std::max(1, static_cast<int>(wanted));
  const double h = period / steps, theta = options.theta;

  // Constant operators of the step.
  const Eigen::MatrixXd iteration_matrix = Eigen::MatrixXd(s.mass + h * theta * s.damping + h * h * theta * theta * s.stiffness);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(iteration_matrix);
  const int laws = static_cast<int>(model.laws.size());
  std::vector<Eigen::MatrixXd> response(laws);  // Y_l = h Ŵ⁻¹ W_l s_l (n x d_l)
  for (int l = 0; l < laws; ++l) {
    const auto& attached = model.laws[l];
    response[l] = h * lu.solve(attached.attachment.transposeDense(n, attached.law->forceSign()));
  }
  // coupling[l][m] = W_l Y_m (the Delassus blocks): velocity of law l's
  // components per unit force of law m.
  std::vector<std::vector<LocalMatrix>> coupling(laws, std::vector<LocalMatrix>(laws));
  for (int l = 0; l < laws; ++l)
    for (int m = 0; m < laws; ++m) {
      const int dl = model.laws[l].law->dimension(), dm = model.laws[m].law->dimension();
      coupling[l][m].resize(dl, dm);
      for (int a = 0; a < dl; ++a) coupling[l][m].row(a) = model.laws[l].attachment.rowTimes(response[m], a);
    }

  auto forcing = [&](double t, Eigen::VectorXd& f) {
    f.setZero();
    for (const auto& load : s.loads) f[load.dof] += load.at(model.omega * t);
  };

  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), v = Eigen::VectorXd::Zero(n);
  const int nb = model.basis.size();
  if (initial_full.size() > 0)
    for (int i = 0; i < n; ++i) stateAtZero(model.basis, initial_full.data() + i * nb, model.omega, &x[i], &v[i]);

  int components = model.lawComponents();
  TimeReference ref;
  ref.step = h;
  ref.steps_per_period = steps;
  ref.displacement.resize(steps, n);
  ref.velocity.resize(steps, n);
  ref.force.resize(steps, components);

  std::vector<LocalVector> lambda(laws);
  for (int l = 0; l < laws; ++l) lambda[l] = LocalVector::Zero(model.laws[l].law->dimension());
  std::vector<LocalVector> lambda_start = lambda;
  Eigen::VectorXd f0(n), f1(n), rhs(n), v_free(n), v_new(n);
  StepProblem problem;
  problem.h = h;
  problem.theta = theta;
  problem.restitution = options.restitution;
  double t = 0.0;

  for (int p = 0; p < options.max_periods; ++p) {
    const Eigen::VectorXd x_period_start = x, v_period_start = v;
    for (int k = 0; k < steps; ++k) {
      t = (static_cast<double>(p) * steps + k) * h;
      forcing(t, f0);
      forcing(t + h, f1);
      rhs.noalias() = s.mass * v;
      rhs += h * (theta * f1 + (1.0 - theta) * f0);
      rhs.noalias() -= h * (1.0 - theta) * (s.damping * v);
      rhs.noalias() -= h * (s.stiffness * x);
      rhs.noalias() -= h * h * theta * (1.0 - theta) * (s.stiffness * v);
      v_free = lu.solve(rhs);
      // Local problems: exact for one law, block Gauss–Seidel for several.
      lambda_start = lambda;  // internal states (a slider) start from the previous step
      const int sweeps = laws > 1 ? 100 : 1;
      for (int sweep = 0; sweep < sweeps; ++sweep) {
        double change = 0.0;
        for (int l = 0; l < laws; ++l) {
          const auto& attached = model.laws[l];
          const int d = attached.law->dimension();
          problem.x_start.resize(d);
          problem.v_start.resize(d);
          problem.u_free.resize(d);
          for (int a = 0; a < d; ++a) {
            problem.x_start[a] = attached.attachment.gather(x, a);
            problem.v_start[a] = attached.attachment.gather(v, a);
            problem.u_free[a] = attached.attachment.gather(v_free, a);
          }
          for (int m = 0; m < laws; ++m)
            if (m != l) problem.u_free += coupling[l][m] * lambda[m];
          problem.delassus = coupling[l][l];
          problem.force_start = lambda_start[l];
          const LocalVector next = attached.law->solveStep(problem);
          change = std::max(change, (next - lambda[l]).cwiseAbs().maxCoeff());
          lambda[l] = next;
        }
        if (change <= 1e-14) break;
      }
      v_new = v_free;
      for (int l = 0; l < laws; ++l) v_new.noalias() += response[l] * lambda[l];
      x += h * (theta * v_new + (1.0 - theta) * v);
      v = v_new;
      // Record the last period: sample (k + 1) mod steps is t = (k+1) h.
      const int sample = (k + 1) % steps;
      ref.displacement.row(sample) = x.transpose();
      ref.velocity.row(sample) = v.transpose();
      for (int l = 0, q = 0; l < laws; ++l)
        for (int a = 0; a < lambda[l].size(); ++a, ++q) ref.force(sample, q) = lambda[l][a];
    }
    ref.periods = p + 1;
    const double scale = std::max({ref.displacement.cwiseAbs().maxCoeff(), ref.velocity.cwiseAbs().maxCoeff(), 1e-300});
    ref.periodicity_error =
        std::max((x - x_period_start).cwiseAbs().maxCoeff(), (v - v_period_start).cwiseAbs().maxCoeff()) / scale;
    if (on_period) on_period(ref.periods, ref.periodicity_error);
    if (!std::isfinite(ref.periodicity_error)) break;
    if (p > 0 && ref.periodicity_error <= options.periodic_tolerance) {
      ref.periodic = true;
      break;
    }
    if (options.max_seconds > 0.0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count() >= options.max_seconds) {
      ref.timed_out = true;
      break;
    }
  }

  // Fourier coefficients of the last period on the model's basis.
  FourierTransform transform(model.basis, steps);
  ref.coefficients.setZero((n + components) * nb);
  Eigen::VectorXd column(steps);
  for (int i = 0; i < n; ++i) {
    column = ref.displacement.col(i);
    transform.project(column.data(), ref.coefficients.data() + i * nb);
  }
  for (int q = 0; q < components; ++q) {
    column = ref.force.col(q);
    transform.project(column.data(), ref.coefficients.data() + (n + q) * nb);
  }
  ref.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
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
