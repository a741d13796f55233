// eqhb-hill: Hill's method (harmonic-balance stability) against the exact
// Floquet multipliers of the shooting orbits. Three tables:
//  1. per scene and ω, the Hill multipliers' distance to the exact ones as H
//     grows (each exact multiplier matched to the nearest Hill one);
//  2. along frequency-response curves, the share of points whose stable /
//     unstable verdict agrees with shooting;
//  3. the cost of the stability check relative to the solve, per point.
// Prints Markdown; --out DIR also writes DIR/hill.md.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/stability/curve_stability.h"
#include "eqhb/stability/hill_stability.h"
#include "exact_reference.h"
#include "report_number.h"

namespace {

using namespace eqhb;
using Complex = std::complex<double>;

std::string number(double x, int digits = 3) { return bench::reportNumber(x, digits); }

std::string problem(const std::string& name) { return std::string(EQHB_PROBLEMS_DIR) + "/" + name; }

// A law that hits a rigid wall: the restitution matters.
bool hasWall(const HbModel& model) {
  const auto site = piecewiseLinearSite(*model.laws[0].law);
  return site && site->rigidWall();
}

// Harmonic balance at H, as the reference orbit starts (exact_reference.h).
Eigen::VectorXd harmonicBalance(HbModel& model, int harmonics, bool* converged) {
  model = bench::onHarmonics(model, harmonics);
  return bench::referenceHarmonicBalance(model, converged);
}

orbits::ShootingResult shoot(const HbModel& model, double restitution, const Eigen::VectorXd& hb) {
  try {
    const auto flow = orbits::makeFlow(model, restitution);
    return orbits::shootFromHarmonicBalance(*flow, model, hb, orbits::ShootingOptions());
  } catch (const std::exception& e) {
    orbits::ShootingResult r;
    r.failure = e.what();
    return r;
  }
}

// max over exact multipliers of the distance to the nearest Hill multiplier.
double multiplierDistance(const HillResult& hill, const Eigen::VectorXcd& exact) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < exact.size(); ++i) {
    double best = INFINITY;
    for (const auto& e : hill.exponents) best = std::min(best, std::abs(e.multiplier - exact[i]));
    worst = std::max(worst, best);
  }
  return worst;
}

std::string multipliersText(const std::vector<Complex>& rho, int most = 4) {
  std::ostringstream s;
  for (int i = 0; i < static_cast<int>(rho.size()) && i < most; ++i) {
    if (i) s << ", ";
    s << number(rho[i].real(), 4);
    if (std::abs(rho[i].imag()) > 1e-6) s << (rho[i].imag() < 0 ? " − " : " + ") << number(std::abs(rho[i].imag()), 4) << "i";
  }
  return s.str();
}

struct ConvergenceCase {
  std::string file;
  double omega;
  double restitution;
};

void convergenceTable(std::ostream& md, bool quick) {
  const std::vector<ConvergenceCase> cases = {
      {"cubic.toml", 0.5, 0.0},          {"friction-1d.toml", 0.308, 0.0}, {"friction-1d.toml", 0.4, 0.0},
      {"friction-1d.toml", 0.55, 0.0},   {"friction-2d-sliding.toml", 0.6, 0.0},
      {"contact.toml", 0.5, 1.0},        {"friction-2d.toml", 0.1, 0.0}};
  const std::vector<int> harmonics = quick ? std::vector<int>{5, 10} : std::vector<int>{5, 10, 20, 40};
  md << "## Hill multipliers against the exact ones as H grows\n\n"
     << "Distance = max over the exact multipliers of |ρ_exact − nearest ρ_Hill|; radius = Hill's spectral "
        "radius (exact in the header). Contact: the exact orbit with restitution e = 1 (harmonic balance has no "
        "impact law and approaches that orbit).\n\n";
  for (const auto& c : cases) {
    HbModel model = loadScene(problem(c.file)).model;
    model.omega = c.omega;
    bool ok = false;
    HbModel reference_model = model;
    const Eigen::VectorXd hb = harmonicBalance(reference_model, harmonics.back(), &ok);
    const auto orbit = shoot(reference_model, c.restitution, hb);
    md << "### " << c.file.substr(0, c.file.size() - 5) << ", ω = " << c.omega
       << (hasWall(model) ? ", e = " + number(c.restitution) : "") << "\n\n";
    if (orbit.converged) {
      std::vector<Complex> exact(orbit.multipliers.data(), orbit.multipliers.data() + orbit.multipliers.size());
      md << "Exact (shooting): " << multipliersText(exact) << "; radius " << number(orbit.spectral_radius, 5)
         << ", " << (orbit.stable ? "stable" : "**unstable**") << ".\n\n";
    } else {
      md << "No exact orbit (" << orbit.failure << "): Hill's verdict only.\n\n";
    }
    md << "| H | HB converged | Hill multipliers (leading) | radius | distance | verdict agrees |\n|---|---|---|---|---|---|\n";
    for (int h : harmonics) {
      HbModel m = model;
      bool converged = false;
      const Eigen::VectorXd full = harmonicBalance(m, h, &converged);
      if (!converged) {
        md << "| " << h << " | no | | | | |\n";
        continue;
      }
      const HillResult hill = hillStability(m, full);
      std::vector<Complex> rho;
      for (const auto& e : hill.exponents) rho.push_back(e.multiplier);
      md << "| " << h << " | yes | " << (hill.failure.empty() ? multipliersText(rho) : hill.failure) << " | "
         << number(hill.spectral_radius, 5) << " | "
         << (orbit.converged ? number(multiplierDistance(hill, orbit.multipliers), 2) : "—") << " | "
         << (orbit.converged ? (hill.stable == orbit.stable ? "yes" : "**no**") : (hill.stable ? "(stable)" : "(unstable)"))
         << " |\n";
    }
    md << "\n";
  }
}

struct CurveCase {
  std::string file;
  bool arclength;
  double from, to, step;
  int stride;  // every stride-th point checked by shooting
  double restitution;
};

void curveTables(std::ostream& md, bool quick) {
  const std::vector<CurveCase> cases = {
      {"cubic.toml", true, 0.4, 1.6, 0.02, quick ? 60 : 10, 0.0},
      {"friction-1d.toml", false, 0.1, 0.8, quick ? 0.05 : 0.01, 1, 0.0},
      {"friction-2d-sliding.toml", false, 0.3, 1.2, quick ? 0.1 : 0.02, 1, 0.0},
      {"contact.toml", false, 0.3, 0.9, quick ? 0.1 : 0.02, 1, 1.0},
      {"stribeck.toml", false, 0.1, 0.8, quick ? 0.05 : 0.01, 1, 0.0}};
  std::ostringstream cost;
  md << "## Stability along curves: Hill against shooting\n\n"
     << "Each checked point: Hill's verdict on the harmonic-balance solution vs the shooting orbit started from "
        "it (points where shooting fails are counted apart). Cost: Hill's time over the corrector's time, per "
        "point (median) and in total.\n\n"
     << "| scene | curve | points | checked | agree | share | shooting failed | Hill unstable | "
        "bifurcations (Hill) |\n|---|---|---|---|---|---|---|---|---|\n";
  cost << "| scene | H | pencil unknowns | Hill ms/point (median) | solve ms/point (median) | ratio (median) | "
          "ratio (total) |\n|---|---|---|---|---|---|---|\n";
  for (const auto& c : cases) {
    const Scene scene = loadScene(problem(c.file));
    ContinuationOptions options;
    options.from = c.from;
    options.to = c.to;
    options.step = c.step;
    auto solver = makeSolver("dogleg");
    SolverOptions solver_options;
    Curve curve = c.arclength ? sweepArclength(scene.model, *solver, solver_options, options)
                              : sweepSequential(scene.model, *solver, solver_options, options);
    const CurveStability stability = analyseCurveStability(scene.model, curve);
    int checked = 0, agree = 0, failed = 0, unstable = 0;
    std::vector<double> hill_ms, solve_ms, ratio;
    for (size_t i = 0; i < curve.points.size(); ++i) {
      const CurvePoint& p = curve.points[i];
      if (!p.stable) continue;
      unstable += !*p.stable;
      hill_ms.push_back(1e3 * stability.points[i].seconds);
      solve_ms.push_back(1e3 * p.seconds);
      ratio.push_back(stability.points[i].seconds / std::max(p.seconds, 1e-9));
      if (i % c.stride != 0) continue;
      HbModel at = scene.model;
      at.omega = p.omega;
      const auto orbit = shoot(at, c.restitution, p.full);
      if (!orbit.converged) {
        ++failed;
        continue;
      }
      ++checked;
      agree += *p.stable == orbit.stable;
    }
    std::map<std::string, int> kinds;
    for (const auto& b : stability.bifurcations) ++kinds[b.kind];
    std::string kinds_text;
    for (const auto& [k, count] : kinds) kinds_text += (kinds_text.empty() ? "" : ", ") + k + " " + std::to_string(count);
    md << "| " << scene.name << " | " << (c.arclength ? "arclength " : "sequential ") << c.from << "–" << c.to
       << " (step " << c.step << (c.stride > 1 ? ", every " + std::to_string(c.stride) + "th checked" : "") << ") | "
       << curve.points.size() << " | " << checked << " | " << agree << " | "
       << (checked ? number(100.0 * agree / checked, 4) + " %" : "—") << " | " << failed << " | " << unstable << " | "
       << (kinds_text.empty() ? "none" : kinds_text) << " |\n";
    auto median = [](std::vector<double> v) -> double {
      if (v.empty()) return NAN;
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    const int pencil = stability.points.empty() ? 0 : [&] {
      for (const auto& h : stability.points)
        if (h.pencil_size) return h.pencil_size;
      return 0;
    }();
    cost << "| " << scene.name << " | " << scene.model.basis.count() << " " << HarmonicSet::kindName(scene.model.basis.kind())
         << " | " << pencil << " | " << number(median(hill_ms)) << " | " << number(median(solve_ms)) << " | "
         << number(100.0 * median(ratio)) << " % | "
         << number(100.0 * stability.seconds / std::max(stability.solve_seconds, 1e-12)) << " % |\n";
  }
  md << "\n## Cost of the stability check\n\n" << cost.str() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Hill's method against the exact Floquet multipliers of shooting"};
  std::string out;
  bool quick = false;
  app.add_option("--out", out, "Also write DIR/hill.md");
  app.add_flag("--quick", quick, "Fewer harmonics and points");
  CLI11_PARSE(app, argc, argv);
  std::ostringstream md;
  md << "# Stability by Hill's method against exact Floquet multipliers\n\n"
     << "Timings on a shared machine: compare ratios within one run.\n\n";
  convergenceTable(md, quick);
  curveTables(md, quick);
  std::cout << md.str();
  if (!out.empty()) std::ofstream(out + "/hill.md") << md.str();
  return 0;
}
