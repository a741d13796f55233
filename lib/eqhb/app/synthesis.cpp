#include "eqhb/app/synthesis.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>
#include <optional>

#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/modes/backbone_refinement.h"

namespace eqhb::app {

namespace {

constexpr int kRefinement = 8;  // modes added between two of the backbone's near the peak

// The DOF with the largest max|x| at the synthesised peak.
int peakDof(const ModeSynthesis& s) {
  return static_cast<int>(std::max_element(s.peak_max_abs.begin(), s.peak_max_abs.end()) - s.peak_max_abs.begin());
}

// The synthesised curve of DOF `dof` as (Ω, A) up to the peak: the lower
// branch up, the peak, the upper branch back down.
std::vector<std::pair<double, double>> synthesisedCurve(const ModeSynthesis& s, int dof) {
  std::vector<std::pair<double, double>> lower, upper;
  for (const SynthesisPoint& p : s.points)
    if (p.amplitude <= s.peak_amplitude) (p.upper ? upper : lower).emplace_back(p.omega, p.max_abs[dof]);
  lower.emplace_back(s.peak_omega, s.peak_max_abs[dof]);
  lower.insert(lower.end(), upper.begin(), upper.end());
  return lower;
}

// The distance from (Ω, A) to the synthesised curve in the plane scaled by
// `width` in Ω and `height` in A: where the resonance bends, the curve is
// steep or turns back, and a difference in A at the same Ω says little.
double distanceToCurve(const std::vector<std::pair<double, double>>& curve, double omega, double amplitude,
                       double width, double height) {
  double nearest = std::numeric_limits<double>::infinity();
  const Eigen::Vector2d q(omega / width, amplitude / height);
  for (size_t i = 1; i < curve.size(); ++i) {
    const Eigen::Vector2d p0(curve[i - 1].first / width, curve[i - 1].second / height);
    const Eigen::Vector2d p1(curve[i].first / width, curve[i].second / height);
    const Eigen::Vector2d d = p1 - p0;
    const double t = d.squaredNorm() > 0.0 ? std::clamp((q - p0).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    nearest = std::min(nearest, (p0 + t * d - q).norm());
  }
  return nearest;
}

// The Ω band where the synthesised max|x_dof| is at least half its peak.
std::pair<double, double> halfPeakBand(const ModeSynthesis& s, int dof) {
  double low = s.peak_omega, high = s.peak_omega;
  for (const SynthesisPoint& p : s.points)
    if (p.max_abs[dof] >= 0.5 * s.peak_max_abs[dof] && p.amplitude <= s.peak_amplitude) {
      low = std::min(low, p.omega);
      high = std::max(high, p.omega);
    }
  return {low, high};
}

}  // namespace

SynthesisComparison compareWithForcedSweep(const SceneSettings& scene, const ModesRun& run, const ModesOptions& modes,
                                           SweepOptions sweep) {
  SynthesisComparison c;
  c.synthesis = synthesizeForcedResponse(run.scene.model, run.backbone);
  if (c.synthesis.closed) {
    // The backbone's grid (tens of points a decade) leaves a few points
    // across a resonance: more modes there, from a quarter of the peak's
    // amplitude (half its response and below) to twice it.
    Backbone dense = run.backbone;
    auto solver = makeSolver(modes.solver);
    const double peak = c.synthesis.peak_amplitude;
    c.refinement_points = refineBackbone(run.scene.model, *solver, modes.solver_options,
                                         run.scene.at_rest ? &*run.scene.at_rest : nullptr, 0.25 * peak, 2.0 * peak,
                                         kRefinement, &dense);
    c.synthesis = synthesizeForcedResponse(run.scene.model, dense);
  }
  const ModeSynthesis& s = c.synthesis;
  if (!s.closed) {
    if (c.synthesis.peak_below_from) {
      c.not_compared = "the forcing drives this mode only below the backbone's smallest amplitude (from = " +
                       formatNumber(run.options.from) +
                       "): its work on the mode is small (a forcing nearly orthogonal to it); give a smaller from";
      return c;
    }
    double reached = 0.0;
    for (const BackbonePoint& p : run.backbone.points)
      if (p.converged) reached = std::max(reached, p.amplitude);
    c.not_compared = "the synthesised response has no peak up to the backbone's largest converged amplitude (" +
                     formatNumber(reached) + (reached < 0.999 * run.options.to ? ", short of to = " : ", to = ") +
                     formatNumber(run.options.to) + ")" +
                     (reached < 0.999 * run.options.to ? "" : ": give a larger to");
    return c;
  }
  c.dof = peakDof(s);
  auto [low, high] = halfPeakBand(s, c.dof);
  // From the linear mode's frequency to the peak's: a resonance that bends
  // (hardening, softening) is reached along its branch from there, which a
  // sweep started cold beside the peak can miss (landing on the other
  // branch between the folds); arclength follows the folds.
  low = std::min(low, run.backbone.start.omega);
  high = std::max(high, run.backbone.start.omega);
  const double margin = 0.25 * std::max(high - low, 1e-3 * s.peak_omega);
  sweep.from = std::max(low - margin, 0.5 * low);
  sweep.to = high + margin;
  sweep.arclength = true;
  const auto start = std::chrono::steady_clock::now();
  SweepResult forced = app::sweep(scene, sweep);
  c.forced_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  c.forced = std::move(forced.curve);

  for (const CurvePoint& p : c.forced.points)
    if (p.converged && p.max_abs[c.dof] > c.forced_peak_amplitude) {
      c.forced_peak_amplitude = p.max_abs[c.dof];
      c.forced_peak_omega = p.omega;
    }
  if (!(c.forced_peak_amplitude > 0.0)) {
    c.not_compared = "no point of the forced sweep converged";
    return c;
  }
  c.peak_amplitude_error = (s.peak_max_abs[c.dof] - c.forced_peak_amplitude) / c.forced_peak_amplitude;
  c.peak_omega_error = (s.peak_omega - c.forced_peak_omega) / c.forced_peak_omega;
  double band_low = c.forced_peak_omega, band_high = c.forced_peak_omega;
  for (const CurvePoint& p : c.forced.points)
    if (p.converged && p.max_abs[c.dof] >= 0.5 * c.forced_peak_amplitude) {
      ++c.band_points;
      band_low = std::min(band_low, p.omega);
      band_high = std::max(band_high, p.omega);
    }
  c.band_width = std::max(band_high - band_low, 1e-6 * c.forced_peak_omega);
  const auto curve = synthesisedCurve(s, c.dof);
  for (const CurvePoint& p : c.forced.points)
    if (p.converged && p.max_abs[c.dof] >= 0.5 * c.forced_peak_amplitude)
      c.band_error = std::max(c.band_error, distanceToCurve(curve, p.omega, p.max_abs[c.dof], c.band_width,
                                                            c.forced_peak_amplitude));
  return c;
}

}  // namespace eqhb::app
