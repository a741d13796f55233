#include "eqhb/output/synthesis_writers.h"

#include <cstdio>

#include "eqhb/harmonic_balance/hb_solution.h"

namespace eqhb::output {

nlohmann::json synthesisJson(const app::SynthesisComparison& c) {
  const ModeSynthesis& s = c.synthesis;
  nlohmann::json points = nlohmann::json::array();
  for (const SynthesisPoint& p : s.points)
    points.push_back({{"omega", p.omega},
                      {"amplitude", p.amplitude},
                      {"branch", p.upper ? "upper" : "lower"},
                      {"max_abs", p.max_abs}});
  nlohmann::json out = {{"closed", s.closed},
                        {"refinement_points", c.refinement_points},
                        {"peak", {{"amplitude", s.peak_amplitude}, {"omega", s.peak_omega}, {"max_abs", s.peak_max_abs}}},
                        {"points", points},
                        {"not_compared", c.not_compared.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.not_compared)}};
  if (!c.not_compared.empty() && c.forced.points.empty()) return out;
  nlohmann::json forced = nlohmann::json::array();
  for (const CurvePoint& p : c.forced.points)
    forced.push_back({{"omega", p.omega},
                      {"converged", p.converged},
                      {"max_abs", p.converged ? nlohmann::json(p.max_abs[c.dof]) : nlohmann::json(nullptr)}});
  out["dof"] = c.dof + 1;
  out["forced"] = {{"points", forced},
                   {"failed_points", c.forced.failed_points},
                   {"seconds", c.forced_seconds},
                   {"peak", {{"omega", c.forced_peak_omega}, {"max_abs", c.forced_peak_amplitude}}}};
  out["errors"] = {{"peak_amplitude", c.peak_amplitude_error},
                   {"peak_omega", c.peak_omega_error},
                   {"band_distance", c.band_error},
                   {"band_points", c.band_points},
                   {"band_width", c.band_width}};
  return out;
}

void writeSynthesisText(std::ostream& out, const app::SynthesisComparison& c) {
  const ModeSynthesis& s = c.synthesis;
  char line[320];
  if (!s.closed || c.forced.points.empty()) {
    out << "synthesis (single nonlinear mode): " << (c.not_compared.empty() ? "no peak" : c.not_compared) << "\n";
    return;
  }
  const std::string x = dofLabel(c.dof);
  std::snprintf(line, sizeof line,
                "synthesis (single nonlinear mode): peak max|%s| = %.6g at omega = %.8g (modal amplitude %.5g; %d modes "
                "added near it)\n",
                x.c_str(), s.peak_max_abs[c.dof], s.peak_omega, s.peak_amplitude, c.refinement_points);
  out << line;
  const CurvePoint& first = c.forced.points.front();
  const CurvePoint& last = c.forced.points.back();
  std::snprintf(line, sizeof line,
                "forced sweep %.6g .. %.6g (%d points, %d failed, %.3g s): peak max|%s| = %.6g at omega = %.8g\n",
                first.omega, last.omega, static_cast<int>(c.forced.points.size()), c.forced.failed_points,
                c.forced_seconds, x.c_str(), c.forced_peak_amplitude, c.forced_peak_omega);
  out << line;
  if (!c.not_compared.empty()) {
    out << "not compared: " << c.not_compared << "\n";
    return;
  }
  std::snprintf(line, sizeof line,
                "synthesis - forced: peak amplitude %+.3g %%, peak omega %+.3g %%; forced points above half the "
                "peak (%d, over %.4g in omega) at most %.3g %% of the peak or of that band away from the synthesis\n",
                100.0 * c.peak_amplitude_error, 100.0 * c.peak_omega_error, c.band_points, c.band_width,
                100.0 * c.band_error);
  out << line;
}

}  // namespace eqhb::output
