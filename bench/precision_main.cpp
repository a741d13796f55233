// eqhb-precision: work–precision against the exact periodic orbits. Per
// scene where shooting applies, the error of harmonic balance against the
// exact orbit vs the median time per solve, with H (and N) varying along
// each curve, one curve per law form, ρ policy, system and backend, and the
// variant "harmonic balance followed by shooting"; then the convergence
// rate in H of each curve. --out DIR writes precision.csv, precision.json
// and precision.md (the rates table); bench/precision_charts.py draws the
// charts and appends the report section.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/scenes/scene.h"
#include "precision_study.h"
#include "report_number.h"

namespace {

using namespace eqhb;
using namespace eqhb::bench;

std::string number(double x, int digits = 3) { return bench::reportNumber(x, digits, "–"); }

// The scene's own discretisation, solved by the own dogleg, as the start of
// the reference orbit.
ExactOrbit referenceOrbit(const PrecisionScene& c) {
  const Scene scene = loadScene(c.file, {"harmonic_balance.omega=" + number(c.omega, 17)});
  const HbModel& model = scene.model;
  return exactOrbit(model, c.restitution, referenceHarmonicBalance(model));
}

// The scene in its alternating frequency–time form on `harmonics`.
HbModel aftModel(const PrecisionScene& c, int harmonics) {
  std::vector<std::string> overrides = {"harmonic_balance.omega=" + number(c.omega, 17)};
  const Scene plain = loadScene(c.file, overrides);
  for (const auto& o : lawFormulationOverrides(plain.model, "aft")) overrides.push_back(o);
  return onHarmonics(loadScene(c.file, overrides).model, harmonics);
}

// The AFT solution at the scene's reference H, and (`self_error`) how far
// the one at half that H lies from it: the reference's own error is about
// that distance over 2^p, p the form's rate.
ExactOrbit harmonicBalanceReference(const PrecisionScene& c, double* self_error) {
  bool converged = false;
  const HbModel model = aftModel(c, c.reference_harmonics);
  const Eigen::VectorXd full = referenceHarmonicBalance(model, &converged);
  const ExactOrbit reference = harmonicBalanceOrbit(model, full, converged);
  *self_error = NAN;
  if (!reference.ok()) return reference;
  bool half_converged = false;
  const HbModel half = aftModel(c, c.reference_harmonics / 2);
  const Eigen::VectorXd coarse = referenceHarmonicBalance(half, &half_converged);
  if (half_converged) *self_error = seriesError(half, coarse, reference).sup;
  return reference;
}

// "hb", "hb+shooting" (shooting from HB at each H) or "hb0+shooting" (from HB at H₀ only).
std::string variantName(const PrecisionCurve& c) {
  return c.refine ? (c.coarse_start ? "hb0+shooting" : "hb+shooting") : "hb";
}

nlohmann::json pointJson(const PrecisionPoint& p) {
  auto finite = [](double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); };
  return {{"harmonics", p.harmonics}, {"samples", p.samples},     {"rho", p.rho},
          {"converged", p.converged}, {"failure", p.failure},     {"seconds", p.seconds},
          {"iterations", p.iterations}, {"sup_error", finite(p.sup_error)},
          {"max_abs_error", finite(p.max_abs_error)}};
}

void writeCsvRow(std::ofstream& csv, const PrecisionPoint& p) {
  const auto& c = p.curve;
  csv << '"' << p.scene << "\",\"" << c.name() << "\"," << (c.form.empty() ? "none" : c.form) << ","
      << rhoPolicyName(c.rho) << "," << (c.condensed ? "condensed" : "full") << "," << c.backend << ","
      << variantName(c) << "," << p.harmonics << "," << p.samples << ","
      << std::setprecision(6) << p.rho << "," << (p.converged ? 1 : 0) << ",\"" << p.failure << "\","
      << std::setprecision(6) << p.seconds << "," << p.iterations << "," << std::setprecision(6)
      << (std::isnan(p.sup_error) ? std::string() : number(p.sup_error, 6)) << ","
      << (std::isnan(p.max_abs_error) ? std::string() : number(p.max_abs_error, 6)) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Work-precision against the exact periodic orbits, and convergence rates in H"};
  std::string out_dir, only;
  bool quick = false;
  std::vector<std::string> backends = {"dogleg", "minpack", "dogleg-newton"};
  app.add_option("--out", out_dir, "Directory for precision.csv, precision.json, precision.md");
  app.add_flag("--quick", quick, "H in {5, 10, 20}, one solve per point, the own dogleg and minpack");
  app.add_option("--only", only, "Only the scenes whose label contains this text");
  app.add_option("--backends", backends, "Backends compared on each scene's first form (default: dogleg minpack dogleg-newton)");
  CLI11_PARSE(app, argc, argv);
  if (quick && app.count("--backends") == 0) backends = {"dogleg", "minpack"};
  std::vector<std::string> available;
  for (const auto& entry : registeredSolvers()) available.push_back(entry.name);
  std::vector<std::string> used;
  for (const auto& b : backends)
    if (std::find(available.begin(), available.end(), b) != available.end()) used.push_back(b);
    else std::cerr << "eqhb-precision: backend " << b << " not compiled in, skipped\n";

  const std::string dir = EQHB_PROBLEMS_DIR;
  // beam-damper-elastic (five elastic dampers on 120 DOFs) is measured
  // against its AFT solution at H = 320: shooting it takes minutes per orbit.
  PrecisionScene dampers{dir + "/beam-damper-elastic.toml", 4.0};
  dampers.reference_harmonics = 320;
  dampers.largest_harmonics = 40;
  const std::vector<PrecisionScene> scenes = {
      {dir + "/friction-1d.toml", 0.308}, {dir + "/friction-1d.toml", 0.4},
      {dir + "/friction-1d.toml", 0.55},  {dir + "/coulomb-oscillator.toml", 0.6},
      {dir + "/friction-2d.toml", 0.1},   {dir + "/friction-2d-sliding.toml", 0.6},
      {dir + "/stribeck.toml", 0.4},      {dir + "/cubic.toml", 0.5},
      {dir + "/jenkins-1d.toml", 0.4},    {dir + "/penalty-contact.toml", 0.5}, 
      {dir + "/contact.toml", 0.5, 1.0},  dampers};
  const std::vector<int> harmonics =
      quick ? std::vector<int>{5, 10, 20} : std::vector<int>{5, 7, 10, 14, 20, 28, 40, 56, 80};
  const int repeats = quick ? 1 : 3;

  std::ofstream csv;
  if (!out_dir.empty()) {
    csv.open(out_dir + "/precision.csv");
    csv << "scene,curve,form,rho_policy,system,backend,variant,harmonics,samples,rho,converged,failure,seconds,"
           "iterations,sup_error,max_abs_error\n";
  }
  nlohmann::json json = {{"harmonics", harmonics}, {"repeats", repeats}, {"quick", quick}, {"scenes", nlohmann::json::array()}};
  std::ostringstream rates;
  rates << "| scene | form | ρ policy | variant | rate of sup error | rate of max\\|x\\| error | points fitted | "
           "sup error at H = " << harmonics.back() << " |\n|---|---|---|---|---|---|---|---|\n";
  std::ostringstream failed_references, hb_references;
  for (const PrecisionScene& scene : scenes) {
    if (scene.label().find(only) == std::string::npos) continue;
    const bool hb_reference = scene.reference_harmonics > 0;
    std::cerr << scene.label() << (hb_reference ? ": AFT reference" : ": exact orbit") << std::flush;
    double reference_self_error = NAN;
    const ExactOrbit exact = hb_reference ? harmonicBalanceReference(scene, &reference_self_error) : referenceOrbit(scene);
    nlohmann::json scene_json = {{"scene", scene.label()}, {"exact_converged", exact.ok()}};
    if (hb_reference) {
      scene_json["reference"] = "aft H=" + std::to_string(scene.reference_harmonics);
      scene_json["reference_half_h_distance"] =
          std::isnan(reference_self_error) ? nlohmann::json(nullptr) : nlohmann::json(reference_self_error);
      hb_references << "- " << scene.label() << ": the AFT solution at H = " << scene.reference_harmonics
                    << " (the one at H = " << scene.reference_harmonics / 2 << " lies "
                    << number(reference_self_error) << " from it, sup); H up to " << scene.largest_harmonics
                    << ", the own dogleg's forms and AFT only\n";
    } else {
      scene_json["reference"] = "shooting";
    }
    if (!exact.ok()) {
      std::cerr << " NOT converged (" << exact.orbit.failure << ")\n";
      failed_references << "- " << scene.label() << ": no exact orbit (" << exact.orbit.failure << ")\n";
      json["scenes"].push_back(scene_json);
      continue;
    }
    scene_json["exact_max_abs"] = std::vector<double>(exact.orbit.max_abs.data(),
                                                      exact.orbit.max_abs.data() + exact.orbit.max_abs.size());
    const HbModel model = loadScene(scene.file).model;
    nlohmann::json curves = nlohmann::json::array();
    std::vector<int> ladder;
    for (int h : harmonics)
      if (scene.largest_harmonics == 0 || h <= scene.largest_harmonics) ladder.push_back(h);
    for (const PrecisionCurve& curve : curvesFor(model, used, hb_reference)) {
      std::cerr << "\n  " << curve.name() << std::flush;
      const std::vector<PrecisionPoint> points = runCurve(scene, curve, ladder, exact, repeats);
      const RateFit fit = fitRate(points);
      nlohmann::json point_list = nlohmann::json::array();
      for (const auto& p : points) {
        point_list.push_back(pointJson(p));
        if (csv.is_open()) writeCsvRow(csv, p);
      }
      curves.push_back({{"name", curve.name()}, {"form", curve.form.empty() ? "none" : curve.form},
                        {"rho_policy", rhoPolicyName(curve.rho)}, {"system", curve.condensed ? "condensed" : "full"},
                        {"backend", curve.backend}, {"variant", variantName(curve)},
                        {"rate_sup", std::isnan(fit.sup) ? nlohmann::json(nullptr) : nlohmann::json(fit.sup)},
                        {"rate_max_abs", std::isnan(fit.max_abs) ? nlohmann::json(nullptr) : nlohmann::json(fit.max_abs)},
                        {"points", point_list}});
      // The rates table: the curves on the own dogleg and the scene's system.
      if (curve.backend != "dogleg" || (curve.condensed != suitsCondensedSystem(model.laws))) continue;
      const PrecisionPoint& last = points.back();
      rates << "| " << scene.label() << " | " << (curve.form.empty() ? "–" : curve.form) << " | "
            << rhoPolicyName(curve.rho) << " | "
            << (curve.refine ? (curve.coarse_start ? "HB at H0 + shooting" : "HB + shooting") : "HB") << " | "
            << number(fit.sup, 2) << " | " << number(fit.max_abs, 2) << " | " << fit.points << " | "
            << (last.converged ? number(last.sup_error) : "failed (" + last.failure + ")")
            << (last.harmonics != harmonics.back() ? " (H = " + std::to_string(last.harmonics) + ")" : "") << " |\n";
    }
    std::cerr << "\n";
    scene_json["curves"] = curves;
    json["scenes"].push_back(scene_json);
  }
  std::ostringstream md;
  md << "### Convergence rates in H against the exact orbits\n\n"
     << "Rate = −slope of log(error) vs log(H), least squares over the converged points of H ∈ {";
  for (size_t i = 0; i < harmonics.size(); ++i) md << (i ? ", " : "") << harmonics[i];
  md << "} with error above 1e-10 (own dogleg; condensed system, full for contact). sup = max over the period "
        "and DOFs of |x − x_exact| / max|x_exact|; max|x| = worst relative error of the peak per DOF. A spectral "
        "rate (smooth orbits) reaches rounding within a few points: its slope is only indicative. "
        "HB + shooting: the harmonic-balance solution at H as the start of shooting, then the exact orbit's "
        "Fourier truncation to the same H harmonics (its max|x| as delivered is the exact orbit's); HB at H0 + "
        "shooting: harmonic balance only at H0 = " << harmonics.front() << ", the orbit projected on each H.\n\n"
     << rates.str() << "\n";
  if (!hb_references.str().empty())
    md << "Scenes measured against a harmonic-balance reference instead of the exact orbit:\n\n"
       << hb_references.str() << "\n";
  if (!failed_references.str().empty()) md << "Scenes without a reference:\n\n" << failed_references.str() << "\n";
  std::cout << md.str();
  if (!out_dir.empty()) {
    std::ofstream(out_dir + "/precision.md") << md.str();
    std::ofstream(out_dir + "/precision.json") << json.dump(1) << "\n";
  }
  return 0;
}
