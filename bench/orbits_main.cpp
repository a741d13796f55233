// eqhb-orbits: the exact periodic orbits as references of truth. Per scene:
// the orbit found by shooting from harmonic balance (max|x|, period
// residual, Floquet multipliers, time per orbit), then the Moreau–Jean
// reference's error against it as h → 0 and the harmonic-balance error
// against it as H grows, with the observed rates. Prints Markdown; --out DIR
// also writes DIR/orbits.md.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/references/time_integrator.h"
#include "eqhb/scenes/scene.h"
#include "error_estimates.h"
#include "exact_reference.h"
#include "report_number.h"

namespace {

using namespace eqhb;

struct Case {
  std::string file;
  double omega;
  double restitution;
};

std::string number(double x, int digits = 3) { return bench::reportNumber(x, digits); }

Eigen::VectorXd harmonicBalance(const HbModel& model, int harmonics, bool* converged) {
  return bench::referenceHarmonicBalance(bench::onHarmonics(model, harmonics), converged);
}

// Harmonic balance (coefficients on `model`'s basis of H) against the exact orbit.
std::pair<double, double> hbError(const HbModel& model, int harmonics, const Eigen::VectorXd& full,
                                  const bench::ExactOrbit& exact) {
  HbModel m = model;
  m.basis = HarmonicSet(model.basis.kind(), harmonics);
  double sup = 0.0;
  Eigen::VectorXd max_hb = Eigen::VectorXd::Zero(model.structure.dofs());
  for (size_t s = 0; s < exact.times.size(); ++s) {
    const Eigen::VectorXd y = orbits::harmonicState(m, full, exact.times[s]);
    const int n = m.structure.dofs();
    for (int i = 0; i < n; ++i) {
      sup = std::max(sup, std::abs(y[i] - exact.displacement(s, i)));
      max_hb[i] = std::max(max_hb[i], std::abs(y[i]));
    }
  }
  // The largest |x_i| of the series: refined around the best sample by
  // golden-section search (the samples alone are 1e-6 off at a peak).
  const double dt = exact.times[1] - exact.times[0];
  for (int i = 0; i < m.structure.dofs(); ++i) {
    size_t best = 0;
    for (size_t s = 0; s < exact.times.size(); ++s)
      if (std::abs(orbits::harmonicState(m, full, exact.times[s])[i]) >
          std::abs(orbits::harmonicState(m, full, exact.times[best])[i]))
        best = s;
    double a = exact.times[best] - dt, b = exact.times[best] + dt;
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    auto value = [&](double t) { return std::abs(orbits::harmonicState(m, full, t)[i]); };
    for (int it = 0; it < 80; ++it) {
      const double c = b - g * (b - a), d = a + g * (b - a);
      (value(c) > value(d) ? b : a) = (value(c) > value(d) ? d : c);
    }
    max_hb[i] = std::max(max_hb[i], value(0.5 * (a + b)));
  }
  const double max_error = ((max_hb - exact.orbit.max_abs).cwiseAbs().array() / exact.orbit.max_abs.array()).maxCoeff();
  return {sup / exact.orbit.max_abs.maxCoeff(), max_error};
}

// Moreau–Jean (θ = ½) at step h, started from the harmonic-balance solution,
// against the exact orbit at the reference's own instants.
struct MjError {
  bool periodic = false;
  int periods = 0;
  double sup = 0.0, max_abs = 0.0, seconds = 0.0;
};
MjError moreauJeanError(const HbModel& model, double restitution, int steps, const Eigen::VectorXd& hb,
                        const bench::ExactOrbit& exact, int max_periods) {
  TimeOptions options;
  const double period = 2 * M_PI / model.omega;
  options.step = period / steps;
  options.restitution = restitution;
  options.max_periods = max_periods;
  options.periodic_tolerance = 1e-11;
  const TimeReference ref = integrateToSteadyState(model, options, hb);
  MjError out;
  out.periodic = ref.periodic;
  out.periods = ref.periods;
  out.seconds = ref.seconds;
  out.sup = orbits::distanceToOrbit(*orbits::makeFlow(model, restitution), exact.orbit, ref.displacement);
  const int n = model.structure.dofs();
  Eigen::VectorXd max_mj(n);
  for (int d = 0; d < n; ++d) max_mj[d] = ref.displacement.col(d).cwiseAbs().maxCoeff();
  out.max_abs = ((max_mj - exact.orbit.max_abs).cwiseAbs().array() / exact.orbit.max_abs.array()).maxCoeff();
  return out;
}

std::string multipliers(const Eigen::VectorXcd& mu) {
  std::ostringstream s;
  for (int k = 0; k < mu.size(); ++k) {
    if (k) s << ", ";
    s << number(mu[k].real(), 4);
    if (mu[k].imag() != 0.0) s << (mu[k].imag() > 0 ? "+" : "−") << number(std::abs(mu[k].imag()), 4) << "i";
  }
  return s.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Exact periodic orbits as references: Moreau-Jean error vs h and harmonic-balance error vs H"};
  std::string out_dir;
  bool quick = false;
  app.add_option("--out", out_dir, "Directory for orbits.md");
  std::string only;
  app.add_flag("--quick", quick, "Fewer steps and harmonics");
  app.add_option("--only", only, "Only the scenes whose file name contains this text");
  bool estimates_only = false;
  app.add_flag("--estimates-only", estimates_only, "Only the exact orbits and the error estimates of harmonic balance");
  CLI11_PARSE(app, argc, argv);
  const std::string dir = EQHB_PROBLEMS_DIR;
  const std::vector<Case> cases = {{"friction-1d.toml", 0.308, 0.0}, {"friction-1d.toml", 0.4, 0.0},
                                   {"friction-1d.toml", 0.55, 0.0},  {"coulomb-oscillator.toml", 0.6, 0.0},
                                   {"contact.toml", 0.5, 0.0},       {"contact.toml", 0.5, 1.0},
                                   {"friction-2d-sliding.toml", 0.6, 0.0}, {"friction-2d.toml", 0.1, 0.0},
                                   {"stribeck.toml", 0.2, 0.0},      {"stribeck.toml", 0.4, 0.0},
                                   {"cubic.toml", 0.5, 0.0},         {"jenkins-1d.toml", 0.4, 0.0}};
  const std::vector<int> steps = quick ? std::vector<int>{250, 1000} : std::vector<int>{250, 500, 1000, 2000, 4000};
  const std::vector<int> harmonics = quick ? std::vector<int>{5, 20} : std::vector<int>{5, 10, 20, 40, 80, 160};
  std::ostringstream md;
  bench::EstimateTally tally;
  auto flush = [&](std::ostringstream& text, bool truncate) {
    std::cout << text.str() << std::flush;
    if (!out_dir.empty()) std::ofstream(out_dir + "/orbits.md", truncate ? std::ios::trunc : std::ios::app) << text.str();
    text.str("");
  };
  md << "# Exact periodic orbits as references of truth\n\n"
     << "Shooting from harmonic balance (H = the scene's), event-driven: closed-form phases (Coulomb 1D, Jenkins on one DOF, "
     << "Signorini), Gauss–Legendre order 6 (cubic, Coulomb 2D with stick–slip, Stribeck). "
     << "Errors are relative to max|x| of the exact orbit: `sup` = max over the period and DOFs of |x − x_exact|, "
     << "`max|x|` = relative error of the largest displacement. Moreau–Jean θ = ½ is started from harmonic "
     << "balance and run to periodicity (1e-11) or the period limit.\n\n";
  bool first = true;
  for (const Case& c : cases) {
    if (c.file.find(only) == std::string::npos) continue;
    const Scene scene = loadScene(dir + "/" + c.file, {"harmonic_balance.omega=" + number(c.omega, 17)});
    const HbModel& model = scene.model;
    bool hb_ok = false;
    const Eigen::VectorXd hb = harmonicBalance(model, model.basis.count(), &hb_ok);
    const bench::ExactOrbit exact = bench::exactOrbit(model, c.restitution, hb);
    const auto& o = exact.orbit;
    const auto wall = piecewiseLinearSite(*model.laws[0].law);  // impacts: the restitution matters
    md << "## " << scene.name << ", ω = " << c.omega << (wall && wall->rigidWall() ? ", e = " + number(c.restitution) : "")
       << "\n\n"
       << "exact orbit: " << (o.converged ? "converged" : "NOT converged (" + o.failure + ")") << ", period residual "
       << number(o.period_residual) << ", " << o.iterations << " Newton steps, " << number(o.seconds_per_orbit * 1e3)
       << " ms per orbit (with monodromy), "
       << (o.converged ? std::string(o.stable ? "stable" : "UNSTABLE") + " (spectral radius " + number(o.spectral_radius, 6) + ")" : "")
       << "\n\nmax|x| per DOF:";
    for (int i = 0; i < o.max_abs.size(); ++i) md << " x" << i + 1 << " = " << number(o.max_abs[i], 12);
    md << "\n\nmultipliers: " << multipliers(o.multipliers) << "\n\nevents per period:";
    for (const auto& [kind, count] : o.events) md << " " << kind << " " << count;
    if (!exact.ok()) {
      md << "\n\nno exact orbit" << (o.converged ? " (its sampling run failed)" : "") << ": no error tables.\n\n";
      const std::string text = md.str();
      md.str("");
      std::cout << text << std::flush;
      if (!out_dir.empty()) std::ofstream(out_dir + "/orbits.md", first ? std::ios::trunc : std::ios::app) << text;
      first = false;
      continue;
    }
    const std::vector<int> estimate_harmonics = quick ? std::vector<int>{5, 20} : std::vector<int>{5, 10, 20, 40, 80};
    md << "\n\nerror estimates of harmonic balance (see the summary at the end):\n\n"
       << bench::errorEstimateTable(model, o.max_abs, estimate_harmonics, scene.name + " ω=" + number(c.omega), &tally);
    if (estimates_only) {
      flush(md, first);
      first = false;
      continue;
    }
    md << "\n\n| Moreau–Jean steps per period | periodic (periods) | sup error | max\\|x\\| error | rate | seconds |\n|---|---|---|---|---|---|\n";
    double previous = 0.0;
    for (int s : steps) {
      const MjError e = moreauJeanError(model, c.restitution, s, hb, exact, quick ? 300 : 1500);
      md << "| " << s << " | " << (e.periodic ? "yes" : "NO") << " (" << e.periods << ") | " << number(e.sup) << " | "
         << number(e.max_abs) << " | " << (previous > 0 ? number(std::log2(previous / e.sup), 2) : "") << " | "
         << number(e.seconds, 2) << " |\n";
      previous = e.sup;
    }
    md << "\n| HB harmonics H | converged | sup error | max\\|x\\| error | rate |\n|---|---|---|---|---|\n";
    previous = 0.0;
    int previous_h = 0;
    for (int h : harmonics) {
      bool ok = false;
      const Eigen::VectorXd full = harmonicBalance(model, h, &ok);
      const auto [sup, max_error] = hbError(model, h, full, exact);
      md << "| " << h << " | " << (ok ? "yes" : "no") << " | " << number(sup) << " | " << number(max_error) << " | "
         << (previous > 0 ? number(std::log(previous / sup) / std::log(double(h) / previous_h), 2) : "") << " |\n";
      previous = sup;
      previous_h = h;
    }
    md << "\n";
    const std::string text = md.str();
    md.str("");
    std::cout << text << std::flush;
    if (!out_dir.empty()) {
      // Appended per scene: a long run keeps what it has done.
      std::ofstream file(out_dir + "/orbits.md", first ? std::ios::trunc : std::ios::app);
      file << text;
    }
    first = false;
  }
  md << errorEstimateSummary(tally);
  flush(md, false);
  return 0;
}
