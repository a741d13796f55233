// eqhb-convergence: accuracy of the harmonic balance against the nonsmooth
// time-domain reference, as the number of harmonics grows (continuation in
// H from one H to the next), and accuracy of the reference itself as its
// step shrinks. Writes convergence.csv / .json (error vs H), reference.csv
// (error vs h) and prints the fitted rates.
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/references/time_integrator.h"
#include "eqhb/backends/registry.h"

using namespace eqhb;

namespace {

// Least-squares slope of log(y) against log(x).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!(y[i] > 0.0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++n;
  }
  return n > 1 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : NAN;
}

double maxError(const std::vector<ChannelError>& errors, bool displacements_only) {
  double worst = 0.0;
  for (const auto& e : errors)
    if (!displacements_only || e.label[0] == 'x') worst = std::max(worst, e.relative_l2);
  return worst;
}

struct Settings {
  std::string scene_file = std::string(EQHB_PROBLEMS_DIR) + "/friction-1d.toml", out = "results";
  std::vector<double> omegas = {0.308, 0.4};
  std::vector<int> harmonics = {1, 2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 25, 30, 40, 50, 60, 70, 80};
  std::vector<double> steps = {8e-4, 4e-4, 2e-4, 1e-4, 5e-5};
  double finest = 2.5e-5, reference_step = 1e-4;
  int samples = 4096;
  bool quick = false;
};

// The time reference at the study's step, described in `entry` and printed.
TimeReference referenceAt(const Scene& base, double omega, const Settings& s, nlohmann::json* entry) {
  TimeOptions options;
  options.step = s.reference_step;
  const TimeReference ref = integrateToSteadyState(base.model, options);
  (*entry)["reference"] = {{"step", ref.step}, {"periodic", ref.periodic}, {"periods", ref.periods},
                           {"seconds", ref.seconds},
                           {"max_abs_x1", ref.displacement.col(0).cwiseAbs().maxCoeff()},
                           {"max_abs_x2", ref.displacement.col(1).cwiseAbs().maxCoeff()}};
  std::cout << base.name << " omega = " << omega << ": reference h = " << ref.step << ", "
            << ref.periods << " periods (" << (ref.periodic ? "periodic" : "NOT periodic") << "), "
            << ref.seconds << " s: max|x1| = " << ref.displacement.col(0).cwiseAbs().maxCoeff()
            << ", max|x2| = " << ref.displacement.col(1).cwiseAbs().maxCoeff() << "\n";
  return ref;
}

// The reference's own error vs h, against the finest step: reference_OMEGA.csv,
// and `entry`'s "reference_vs_step", "reference_rate_in_h" and "finest".
void referenceVsStep(const Scene& base, double omega, const Settings& s, nlohmann::json* entry) {
  // Runs are compared through a wide Fourier basis (1000 harmonics), so
  // that the step error is not hidden under the scene's truncation.
  HbModel wide = base.model;
  wide.basis = HarmonicSet(base.model.basis.kind(), 1000);
  wide.samples = 2 * wide.basis.highest() + 1;
  TimeOptions fine_options;
  fine_options.step = s.finest;
  const TimeReference fine = integrateToSteadyState(wide, fine_options);
  std::ofstream rcsv(s.out + "/reference_" + formatNumber(omega) + ".csv");
  rcsv << "step,periods,seconds,max_abs_x1,max_abs_x2,l2_error_vs_finest\n";
  std::vector<double> hs, errs;
  nlohmann::json rows = nlohmann::json::array();
  for (double h : s.steps) {
    TimeOptions o;
    o.step = h;
    const TimeReference r = integrateToSteadyState(wide, o);
    const auto e = compareWithReference(wide, r.coefficients, fine);
    const double err = maxError(e, true);
    hs.push_back(h);
    errs.push_back(err);
    rcsv << r.step << "," << r.periods << "," << r.seconds << "," << r.displacement.col(0).cwiseAbs().maxCoeff()
         << "," << r.displacement.col(1).cwiseAbs().maxCoeff() << "," << err << "\n";
    rows.push_back({{"step", r.step}, {"seconds", r.seconds}, {"max_abs_x1", r.displacement.col(0).cwiseAbs().maxCoeff()},
                    {"max_abs_x2", r.displacement.col(1).cwiseAbs().maxCoeff()}, {"l2_error_vs_finest", err}});
    std::cout << "  reference h = " << r.step << ": max|x1| = " << r.displacement.col(0).cwiseAbs().maxCoeff()
              << ", max|x2| = " << r.displacement.col(1).cwiseAbs().maxCoeff() << ", L2 error vs h = "
              << fine.step << ": " << err << " (" << r.seconds << " s)\n";
  }
  (*entry)["reference_vs_step"] = rows;
  (*entry)["reference_rate_in_h"] = logLogSlope(hs, errs);
  (*entry)["finest"] = {{"step", fine.step}, {"seconds", fine.seconds},
                        {"max_abs_x1", fine.displacement.col(0).cwiseAbs().maxCoeff()},
                        {"max_abs_x2", fine.displacement.col(1).cwiseAbs().maxCoeff()}};
  std::cout << "  reference convergence rate in h: " << logLogSlope(hs, errs) << "\n";
}

// HB error vs H against `ref`, by continuation in H (every H of the study, or
// only 10, 20, 40 and 80): rows of convergence.csv, and `entry`'s
// "hb_vs_harmonics" and "hb_rate_in_H".
void hbVsHarmonics(const TimeReference& ref, double omega, bool every_h, const Settings& s, Solver& solver,
                   std::ostream& csv, nlohmann::json* entry) {
  Eigen::VectorXd previous;
  HbModel previous_model;
  std::vector<double> hx, ex;
  nlohmann::json rows = nlohmann::json::array();
  for (int h : s.harmonics) {
    if (!every_h && h != 10 && h != 20 && h != 40 && h != 80) continue;
    const Scene scene = loadScene(s.scene_file, {"harmonic_balance.omega=" + formatNumber(omega),
                                                 "harmonic_balance.harmonics=" + std::to_string(h),
                                                 "harmonic_balance.samples=" + std::to_string(s.samples)});
    CondensedSystem system(scene.model);
    Eigen::VectorXd z0 = Eigen::VectorXd::Zero(system.size());
    if (previous.size() > 0)
      z0 = system.fromFullCoefficients(transferCoefficients(previous_model, scene.model, previous));
    const SolverResult r = solver.solve(system, z0, {});
    const Eigen::VectorXd full = system.fullCoefficients(r.solution);
    const auto e = compareWithReference(scene.model, full, ref);
    if (r.converged()) {
      previous = full;
      previous_model = scene.model;
      hx.push_back(h);
      ex.push_back(e[1].relative_l2);
    }
    csv << omega << "," << h << "," << r.converged() << "," << r.final_norm << "," << r.iterations << ","
        << r.seconds << "," << e[0].max_abs_hb << "," << e[1].max_abs_hb << "," << e[0].relative_l2 << ","
        << e[1].relative_l2 << "," << e[2].relative_l2 << "," << e[1].relative_max_abs << ","
        << e[1].first_harmonic_error << "\n";
    rows.push_back({{"harmonics", h}, {"converged", r.converged()}, {"residual_norm", r.final_norm},
                    {"iterations", r.iterations}, {"seconds", r.seconds},
                    {"max_abs_x1", e[0].max_abs_hb}, {"max_abs_x2", e[1].max_abs_hb},
                    {"l2_x1", e[0].relative_l2}, {"l2_x2", e[1].relative_l2}, {"l2_lambda1", e[2].relative_l2},
                    {"error_max_abs_x2", e[1].relative_max_abs},
                    {"first_harmonic_error_x2", e[1].first_harmonic_error}});
    std::cout << "  HB H = " << h << ": " << (r.converged() ? "converged" : terminationName(r.termination))
              << ", " << r.seconds << " s, max|x1| = " << e[0].max_abs_hb << ", max|x2| = " << e[1].max_abs_hb
              << ", L2 error x2 = " << e[1].relative_l2 << "\n";
  }
  std::vector<double> fit_h, fit_e;
  for (size_t i = 0; i < hx.size(); ++i)
    if (hx[i] >= 4) fit_h.push_back(hx[i]), fit_e.push_back(ex[i]);
  (*entry)["hb_vs_harmonics"] = rows;
  (*entry)["hb_rate_in_H"] = logLogSlope(fit_h, fit_e);
  std::cout << "  HB convergence rate in H (L2 error of x2, H >= 4): " << logLogSlope(fit_h, fit_e) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"eqhb-convergence: HB error vs harmonics and reference error vs step"};
  Settings s;
  app.add_option("--scene", s.scene_file, "Scene file");
  app.add_option("--omega", s.omegas, "Frequencies (the first gets the full study)");
  app.add_option("--harmonics", s.harmonics, "Harmonic counts H, increasing");
  app.add_option("--samples", s.samples, "N for every H");
  app.add_option("--out", s.out, "Output folder");
  app.add_flag("--quick", s.quick, "Fewer H and steps");
  CLI11_PARSE(app, argc, argv);
  if (s.quick) {
    s.harmonics = {1, 2, 4, 10, 20, 40};
    s.steps = {4e-4, 2e-4, 1e-4};
    s.finest = 5e-5;
  }
  std::filesystem::create_directories(s.out);
  auto solver = makeSolver("dogleg");
  nlohmann::json report;

  std::ofstream csv(s.out + "/convergence.csv");
  csv << "omega,harmonics,converged,residual_norm,iterations,seconds,max_abs_x1,max_abs_x2,"
         "l2_x1,l2_x2,l2_lambda1,error_max_abs_x2,first_harmonic_error_x2\n";
  for (size_t w = 0; w < s.omegas.size(); ++w) {
    const double omega = s.omegas[w];
    const Scene base = loadScene(s.scene_file, {"harmonic_balance.omega=" + formatNumber(omega)});
    nlohmann::json entry = {{"omega", omega}};
    const TimeReference ref = referenceAt(base, omega, s, &entry);
    if (w == 0 || !s.quick) referenceVsStep(base, omega, s, &entry);
    hbVsHarmonics(ref, omega, w == 0, s, *solver, csv, &entry);
    report.push_back(entry);
  }
  std::ofstream(s.out + "/convergence.json") << report.dump(2) << "\n";
  std::cout << "wrote " << s.out << "/convergence.csv, convergence.json, reference_*.csv\n";
  return 0;
}
