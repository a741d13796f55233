#include "eqhb/studies/peak_tracking.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

void PeakOptions::validate(int dofs) const {
  if (!(from > 0.0) || !std::isfinite(from)) throwInputError("from", formatNumber(from), "must be finite and > 0");
  if (!(to > from) || !std::isfinite(to)) throwInputError("to", formatNumber(to), "must be finite and > from");
  if (dof < 0 || dof >= dofs)  // named as the scene numbers DOFs, from 1
    throwInputError("dof", std::to_string(dof + 1), "must be a DOF of the scene, 1.." + std::to_string(dofs));
  if (coarse_points < 3) throwInputError("coarse_points", std::to_string(coarse_points), "must be >= 3");
  if (!(omega_tolerance > 0.0) || omega_tolerance >= 1e-2)
    throwInputError("omega_tolerance", formatNumber(omega_tolerance), "must be in (0, 1e-2)");
  if (max_secant_steps < 2) throwInputError("max_secant_steps", std::to_string(max_secant_steps), "must be >= 2");
  if (max_peaks < 1 || max_peaks > 100) throwInputError("max_peaks", std::to_string(max_peaks), "must be in [1, 100]");
}

namespace {

// A converged point of the branch with its tangent and the peak function.
struct BranchPoint {
  double omega = 0.0;
  Eigen::VectorXd z, dz;  // solution and dz/dω
  double phi = 0.0;       // dA²/dω
  double amplitude2 = 0.0;
};

class BranchProbe {
 public:
  BranchProbe(HbSystem& system, Solver& solver, const SolverOptions& options, int dof)
      : system_(system), solver_(solver), options_(options), dof_(dof), nb_(system.model().basis.size()) {}

  // Solves g(z, ω) = 0 from `guess`, then the tangent and φ; false with why.
  bool solveAt(double omega, const Eigen::VectorXd& guess, BranchPoint* point, std::string* why) {
    if (!setOmega(omega, why)) return false;
    const SolverResult r = solver_.solve(system_, guess, options_);
    ++solves;
    iterations += r.iterations;
    if (!r.converged()) {
      *why = std::string(terminationName(r.termination)) + " at omega = " + formatNumber(omega);
      return false;
    }
    return differentiate(omega, r.solution, point, why);
  }

  int solves = 0, iterations = 0;

 private:
  bool setOmega(double omega, std::string* why) {
    try {
      system_.setOmega(omega);
      return true;
    } catch (const std::exception& e) {
      *why = e.what();
      return false;
    }
  }

  double amplitude2(const Eigen::VectorXd& z) const {
    const Eigen::VectorXd full = system_.fullCoefficients(z);
    const double a = firstHarmonicAmplitude(system_.model().basis, full.data() + dof_ * nb_);
    return a * a;
  }

  bool differentiate(double omega, const Eigen::VectorXd& z, BranchPoint* p, std::string* why) {
    const int n = system_.size();
    Eigen::VectorXd g(n), g_shift(n);
    Eigen::MatrixXd j(n, n);
    if (!system_.residualAndJacobian(z, g, j)) {
      *why = "Jacobian evaluation failed at omega = " + formatNumber(omega);
      return false;
    }
    const double a0 = amplitude2(z);
    const double delta = 1e-7 * std::max(1.0, omega);
    if (!setOmega(omega + delta, why) || !system_.residual(z, g_shift)) {
      if (why->empty()) *why = "residual evaluation failed at omega = " + formatNumber(omega + delta);
      return false;
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(j);
    const Eigen::VectorXd dz = -lu.solve((g_shift - g) / delta);
    if (!dz.allFinite()) {
      *why = "singular Jacobian (no tangent) at omega = " + formatNumber(omega);
      return false;
    }
    // φ by a forward difference along the tangent; with the condensed
    // system x depends on ω also through the condensation, which the
    // system at ω + δ accounts for.
    const double a1 = amplitude2(z + delta * dz);
    p->omega = omega;
    p->z = z;
    p->dz = dz;
    p->amplitude2 = a0;
    p->phi = (a1 - a0) / delta;
    return std::isfinite(p->phi) || (*why = "peak function not finite at omega = " + formatNumber(omega), false);
  }

  HbSystem& system_;
  Solver& solver_;
  const SolverOptions& options_;
  int dof_, nb_;
};

// Secant iteration on φ from `start` inside [lo, hi]; the peak or why not.
bool refinePeak(BranchProbe& probe, const PeakOptions& options, BranchPoint start, double lo, double hi,
                BranchPoint* peak, std::string* why) {
  std::optional<BranchPoint> rising, falling;  // φ > 0 (left of a maximum) and φ < 0 (right of it)
  auto classify = [&](const BranchPoint& p) {
    if (p.phi > 0.0 && (!rising || p.omega > rising->omega)) rising = p;
    if (p.phi < 0.0 && (!falling || p.omega < falling->omega)) falling = p;
  };
  classify(start);
  if (start.phi == 0.0) {
    *peak = start;
    return true;
  }
  const double range = hi - lo;
  const double max_step = 0.1 * (options.to - options.from);
  double step = std::min(1e-3 * (options.to - options.from), 0.25 * range);
  BranchPoint previous, current = start;
  bool have_previous = false;
  for (int k = 0; k < options.max_secant_steps; ++k) {
    const double direction = current.phi > 0.0 ? 1.0 : -1.0;
    double target;
    const bool bracketed = rising && falling && rising->omega < falling->omega;
    const double slope = have_previous ? (current.phi - previous.phi) / (current.omega - previous.omega) : 0.0;
    if (have_previous && slope < 0.0) {
      target = current.omega - current.phi / slope;  // secant towards a maximum
    } else {
      target = current.omega + direction * step;  // uphill until φ changes sign
      step = std::min(2.0 * step, max_step);
    }
    if (bracketed && !(target > rising->omega && target < falling->omega))
      target = 0.5 * (rising->omega + falling->omega);
    target = std::clamp(target, current.omega - max_step, current.omega + max_step);
    target = std::clamp(target, lo, hi);
    if (target == current.omega) {
      *why = "the peak lies outside [" + formatNumber(lo) + ", " + formatNumber(hi) + "] (amplitude still " +
             (direction > 0 ? "rising" : "falling") + " at omega = " + formatNumber(current.omega) + ")";
      return false;
    }
    // Corrector from the tangent predictor; on failure, halve the step.
    BranchPoint next;
    bool ok = false;
    for (int halving = 0; halving < 8 && !ok; ++halving) {
      const Eigen::VectorXd guess = current.z + (target - current.omega) * current.dz;
      ok = probe.solveAt(target, guess, &next, why);
      if (!ok) target = 0.5 * (target + current.omega);
    }
    if (!ok) return false;
    classify(next);
    const double moved = std::abs(next.omega - current.omega);
    previous = current;
    current = next;
    have_previous = true;
    if (moved <= options.omega_tolerance * current.omega || current.phi == 0.0) {
      const bool maximum = (rising && falling && rising->omega <= current.omega + moved &&
                            falling->omega >= current.omega - moved) ||
                           (current.phi - previous.phi) / (current.omega - previous.omega) < 0.0;
      if (!maximum) {
        *why = "stationary amplitude at omega = " + formatNumber(current.omega) + " is not a maximum";
        return false;
      }
      *peak = current;
      return true;
    }
  }
  *why = "no peak within " + std::to_string(options.max_secant_steps) + " secant steps (last omega = " +
         formatNumber(current.omega) + ")";
  return false;
}

// Amplitude at ω from the nearest known point (tangent predictor); false
// with why.
bool amplitudeAt(BranchProbe& probe, const BranchPoint& near, double omega, BranchPoint* point, std::string* why) {
  return probe.solveAt(omega, near.z + (omega - near.omega) * near.dz, point, why);
}

// φ comes from the weak Jacobian's tangent, which a nonsmooth branch
// (stick–slip switching along ω) can get wrong, so the secant may stop
// where φ vanishes but the amplitude still climbs. A peak is accepted only
// if the amplitude at ω* ± h is not above it. Otherwise the maximum is
// found from amplitudes alone: steps uphill, doubling, until the amplitude
// falls, then golden-section search of that bracket (down to 1e-7 ω: the
// amplitude is flat at a maximum, so its value is then exact to ~1e-14).
bool confirmPeak(BranchProbe& probe, const PeakOptions& options, double lo, double hi, BranchPoint* peak,
                 std::string* why) {
  const double h = std::max(1e-4 * (options.to - options.from), 1e3 * options.omega_tolerance * peak->omega);
  BranchPoint left, right;
  const bool has_left = peak->omega - h >= lo, has_right = peak->omega + h <= hi;
  if (has_left && !amplitudeAt(probe, *peak, peak->omega - h, &left, why)) return false;
  if (has_right && !amplitudeAt(probe, *peak, peak->omega + h, &right, why)) return false;
  const double top = peak->amplitude2 * (1.0 + 1e-12);
  const bool left_higher = has_left && left.amplitude2 > top, right_higher = has_right && right.amplitude2 > top;
  if (!left_higher && !right_higher) return true;

  // Bracket a < b < c with A(b) >= A(a), A(c), walking uphill from the peak.
  const double direction = (right_higher && (!left_higher || right.amplitude2 >= left.amplitude2)) ? 1.0 : -1.0;
  BranchPoint a = *peak, b = direction > 0 ? right : left, c;
  double step = h;
  for (int k = 0;; ++k) {
    if (k >= options.max_secant_steps) {
      *why = "amplitude still rising at omega = " + formatNumber(b.omega) + " after " +
             std::to_string(options.max_secant_steps) + " uphill steps";
      return false;
    }
    step = std::min(2.0 * step, 0.1 * (options.to - options.from));
    const double next = std::clamp(b.omega + direction * step, lo, hi);
    if (next == b.omega) {
      *why = "the peak lies outside [" + formatNumber(lo) + ", " + formatNumber(hi) + "] (amplitude still rising at omega = " +
             formatNumber(b.omega) + ")";
      return false;
    }
    if (!amplitudeAt(probe, b, next, &c, why)) return false;
    if (c.amplitude2 <= b.amplitude2) break;
    a = std::move(b);
    b = std::move(c);
  }
  if (a.omega > c.omega) std::swap(a, c);
  // Golden section on [a, c] keeping the best interior point b.
  const double ratio = 0.5 * (3.0 - std::sqrt(5.0));
  while (c.omega - a.omega > 1e-7 * b.omega) {
    const bool right_part = c.omega - b.omega > b.omega - a.omega;
    const double x = right_part ? b.omega + ratio * (c.omega - b.omega) : b.omega - ratio * (b.omega - a.omega);
    BranchPoint trial;
    if (!amplitudeAt(probe, b, x, &trial, why)) return false;
    if (trial.amplitude2 > b.amplitude2) {
      (right_part ? a : c) = std::move(b);
      b = std::move(trial);
    } else {
      (right_part ? c : a) = std::move(trial);
    }
  }
  *peak = std::move(b);
  return true;
}

// Peaks closer than `tolerance` in ω are one (two followed resonances that
// merged, or ripples of a nonsmooth curve): the larger is kept.
void mergeClosePeaks(std::vector<BranchPoint>* peaks, double tolerance) {
  std::sort(peaks->begin(), peaks->end(), [](const auto& a, const auto& b) { return a.omega < b.omega; });
  std::vector<BranchPoint> merged;
  for (auto& p : *peaks) {
    if (!merged.empty() && p.omega - merged.back().omega <= tolerance) {
      if (p.amplitude2 > merged.back().amplitude2) merged.back() = std::move(p);
    } else {
      merged.push_back(std::move(p));
    }
  }
  *peaks = std::move(merged);
}

}  // namespace

PeakResult trackPeak(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                     const PeakOptions& options, const PeakState* warm) {
  options.validate(model.structure.dofs());
  const auto started = std::chrono::steady_clock::now();
  PeakResult result;
  HbModel m = model;
  m.omega = options.from;
  std::unique_ptr<HbSystem> system;
  try {
    system = makeHbSystem(m, options.condensed);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    result.reason = e.what();
    return result;
  }
  BranchProbe probe(*system, solver, solver_options, options.dof);
  const double merge_tolerance = 1e-3 * (options.to - options.from);
  std::vector<BranchPoint> peaks;
  std::string why;

  if (warm && warm->valid()) {
    for (std::size_t k = 0; k < warm->z.size(); ++k) {
      const double omega = warm->omegas[k];
      if (warm->z[k].size() != system->size() || omega < options.from || omega > options.to) continue;
      BranchPoint start, peak;
      if (probe.solveAt(omega, warm->z[k], &start, &why) &&
          refinePeak(probe, options, start, options.from, options.to, &peak, &why) &&
          confirmPeak(probe, options, options.from, options.to, &peak, &why))
        peaks.push_back(std::move(peak));
    }
    mergeClosePeaks(&peaks, merge_tolerance);
    result.start = !peaks.empty() ? "warm" : "cold (warm: " + (why.empty() ? "no usable state" : why) + ")";
  } else {
    result.start = "cold";
  }

  if (peaks.empty()) {
    // Cold: a coarse sweep; its interior local maxima, the largest first,
    // each refined between its grid neighbours.
    ContinuationOptions sweep;
    sweep.from = options.from;
    sweep.to = options.to;
    sweep.step = (options.to - options.from) / (options.coarse_points - 1);
    sweep.min_step = sweep.step * 1e-4;
    sweep.max_step = std::max(1.0, sweep.step);
    sweep.condensed = options.condensed;
    if (options.fallbacks) sweep.fallbacks = *options.fallbacks;
    const Curve curve = sweepSequential(m, solver, solver_options, sweep);
    const int last = static_cast<int>(curve.points.size()) - 1;
    auto amplitude = [&](int i) { return curve.points[i].first_harmonic[options.dof]; };
    int best = -1;
    for (int i = 0; i <= last; ++i) {
      probe.solves += 1;
      probe.iterations += curve.points[i].iterations;
      if (curve.points[i].converged && (best < 0 || amplitude(i) > amplitude(best))) best = i;
    }
    if (best < 0) {
      why = "the coarse sweep over [" + formatNumber(options.from) + ", " + formatNumber(options.to) +
            "] found no solution";
    } else if (best == 0 || best == last) {
      why = "largest amplitude at the edge of [" + formatNumber(options.from) + ", " + formatNumber(options.to) +
            "] (omega = " + formatNumber(curve.points[best].omega) + "): widen the range";
    } else {
      std::vector<int> maxima;
      for (int i = 1; i < last; ++i)
        if (curve.points[i - 1].converged && curve.points[i].converged && curve.points[i + 1].converged &&
            amplitude(i) >= amplitude(i - 1) && amplitude(i) >= amplitude(i + 1))
          maxima.push_back(i);
      if (maxima.empty())
        why = "no local maximum with converged neighbours on the coarse sweep over [" + formatNumber(options.from) +
              ", " + formatNumber(options.to) + "] (" + std::to_string(curve.failed_points) + " of " +
              std::to_string(last + 1) + " points failed)";
      std::sort(maxima.begin(), maxima.end(), [&](int a, int b) { return amplitude(a) > amplitude(b); });
      if (static_cast<int>(maxima.size()) > options.max_peaks) maxima.resize(options.max_peaks);
      for (int i : maxima) {
        BranchPoint start, peak;
        if (probe.solveAt(curve.points[i].omega, system->fromFullCoefficients(curve.points[i].full), &start, &why) &&
            refinePeak(probe, options, start, curve.points[i - 1].omega, curve.points[i + 1].omega, &peak, &why) &&
            confirmPeak(probe, options, options.from, options.to, &peak, &why))
          peaks.push_back(std::move(peak));
      }
      mergeClosePeaks(&peaks, merge_tolerance);
    }
  }

  result.solves = probe.solves;
  result.iterations = probe.iterations;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (peaks.empty()) {
    result.reason = why;
    return result;
  }
  const auto top = std::max_element(peaks.begin(), peaks.end(),
                                    [](const auto& a, const auto& b) { return a.amplitude2 < b.amplitude2; });
  m.omega = top->omega;
  system->setOmega(top->omega);
  const CurvePoint described = describePoint(m, system->fullCoefficients(top->z));
  result.converged = true;
  result.peaks = static_cast<int>(peaks.size());
  result.omega = top->omega;
  result.first_harmonic = described.first_harmonic;
  result.max_abs = described.max_abs;
  for (auto& p : peaks) {
    result.state.omegas.push_back(p.omega);
    result.state.z.push_back(std::move(p.z));
  }
  return result;
}

}  // namespace eqhb
