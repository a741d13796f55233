#include "accuracy_tally.h"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/accuracy/rung_test.h"
#include "eqhb/accuracy/accuracy_target.h"
#include "eqhb/app/rho_candidates.h"
#include "eqhb/app/solve_options.h"
#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/orbits/smooth_flow.h"
#include "report_number.h"

namespace eqhb::bench {

namespace {

std::string number(double x, int digits = 3) { return reportNumber(x, digits); }

// One scene at every ω of `omegas` and every value of `key` in `values`.
void grid(std::vector<TallyCase>& out, const std::string& file, const std::vector<double>& omegas,
          const std::string& key, const std::vector<double>& values) {
  for (double value : values)
    for (double omega : omegas)
      out.push_back({file, omega, {key + "=" + number(value, 6)}, key + " = " + number(value, 6)});
}

struct Measured {
  bool solved = false;     // the solve ran (no exception)
  bool reached = false;    // the target claimed success
  int harmonics = 0;
  std::string test;        // which test decided
  double claimed = 0.0;    // its value
  bool exact = false;      // the true error was measured
  double true_error = 0.0;
  double seconds = 0.0;
  std::string note;
  // The estimate's bias where both were made: true error ÷ estimate of every
  // rung of every ρ candidate tested by the exact orbit and climbed past
  // (its solve at 2H is the estimate's).
  std::vector<double> bias;
};

// The accuracy ladder as `solve --accuracy` runs it (the ρ candidates, the
// first H min(5, the scene's), the default solver), then the true error of
// its answer: max|x| of the chosen solution against the exact orbit shot
// from it, in the target's own measure.
Measured measure(const TallyCase& c, const TallyOptions& o) {
  Measured m;
  app::SceneSettings scene;
  scene.path = std::string(EQHB_PROBLEMS_DIR) + "/" + c.file;
  scene.overrides = c.overrides;
  scene.omega = c.omega;
  const app::SolveOptions defaults;
  AccuracyTestOptions test;
  test.choice = parseAccuracyTestChoice(o.accuracy_test);
  test.safety_factor = o.safety_factor;
  const auto start = std::chrono::steady_clock::now();
  try {
    const app::RhoCandidates candidates = app::rhoCandidates(scene);
    auto solver = makeSolver(defaults.solver);
    const OwnedFallbackChain fallbacks(defaults.fallback, defaults.solver, "fallback");
    const AccuracyChoice choice =
        chooseDiscretisation(candidates.models, o.tolerance, std::min(5, candidates.models.front().basis.count()),
                             o.max_harmonics, *solver, defaults.solver_options, defaults.condensed, test,
                             fallbacks.chain());
    m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m.solved = choice.result.converged();
    m.reached = choice.reached;
    m.harmonics = choice.model.basis.count();
    m.test = accuracyTestName(choice.test);
    m.claimed = choice.error;
    if (!m.reached) m.note = choice.failure;
    for (const auto& ladder : choice.candidate_ladders)
      for (const AccuracyRung& r : ladder)
        if (r.tested && r.test == AccuracyTest::kExactOrbit && r.estimated && r.estimate > 0.0 && r.error > 1e-9)
          m.bias.push_back(r.error / r.estimate);
    if (!m.solved) return m;
    const ExactOrbitError exact = exactOrbitError(choice.model, choice.full);
    m.exact = exact.converged;
    m.true_error = exact.error;
    if (!exact.converged) m.note += (m.note.empty() ? "" : "; ") + exact.failure;
  } catch (const std::exception& e) {
    m.note = e.what();
  }
  return m;
}

}  // namespace

std::vector<TallyCase> accuracyTallyCases() {
  std::vector<TallyCase> out;
  // Two-DOF chain with Coulomb friction: stick-slip below and around the
  // resonance (0.2 to 0.55), sliding above (1.2), three friction levels.
  grid(out, "friction-1d.toml", {0.2, 0.35, 0.55, 1.2}, "law[0].muN", {4.0, 7.2, 10.0});
  // One DOF: from mostly sliding (muN 0.1) to long sticks (0.6).
  grid(out, "coulomb-oscillator.toml", {0.4, 0.6, 0.9, 1.5}, "law[0].muN", {0.1, 0.3, 0.6});
  grid(out, "friction-2d.toml", {0.1, 0.3}, "law[0].muN", {5.0, 8.0});
  grid(out, "friction-2d-sliding.toml", {0.6, 0.9}, "law[0].muN", {8.0});
  // Stribeck with a static limit 1.5 times the dynamic one: scale the
  // forcing instead of the friction to keep that ratio.
  grid(out, "stribeck.toml", {0.2, 0.4, 0.7}, "forcing[0].cos", {14.0, 20.0});
  grid(out, "jenkins-1d.toml", {0.2, 0.4, 0.7}, "law[0].muN", {4.0, 7.2});
  // Signorini contact against the elastic-impact orbit (e = 1, which its
  // harmonic balance approaches): ω = 0.4 stays clear of the wall.
  grid(out, "contact.toml", {0.4, 0.5, 0.55, 0.6}, "forcing[0].cos", {1.0});
  // An elastic wall (penalty spring, exact orbits in closed form): below,
  // at and above the first resonance, a soft and a stiff wall.
  grid(out, "penalty-contact.toml", {0.4, 0.5, 0.7}, "law[0].stiffness", {10.0, 100.0});
  return out;
}

std::string accuracyTally(const std::vector<TallyCase>& cases, const TallyOptions& o) {
  std::ostringstream md;
  md << "`solve --accuracy " << o.tolerance << " --accuracy-test " << o.accuracy_test << " --max-harmonics "
     << o.max_harmonics << "`" << (o.accuracy_test == "estimate" ? ", safety factor " + number(o.safety_factor) : "")
     << "; true error = relative error of max|x| (worst DOF) of the answer against the exact "
     << "orbit shot from it.\n\n"
     << "| scene | ω | changed | reached | H | test | tested error | true error | true ÷ TOL | seconds | note |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  int count = 0, reached = 0, measured = 0, within = 0, within_15 = 0;
  double worst = 0.0, seconds = 0.0;
  std::vector<double> bias;
  std::string worst_case;
  for (const TallyCase& c : cases) {
    if (c.file.find(o.only) == std::string::npos) continue;
    const Measured m = measure(c, o);
    ++count;
    seconds += m.seconds;
    bias.insert(bias.end(), m.bias.begin(), m.bias.end());
    const double ratio = m.true_error / o.tolerance;
    md << "| " << c.file.substr(0, c.file.size() - 5) << " | " << c.omega << " | " << c.label << " | "
       << (m.reached ? "yes" : "no") << " | " << m.harmonics << " | " << m.test << " | " << number(m.claimed) << " | "
       << (m.exact ? number(m.true_error) : "–") << " | " << (m.exact ? number(ratio, 3) : "–") << " | "
       << number(m.seconds, 3) << " | " << m.note << " |\n";
    std::cerr << c.file << " " << c.omega << " " << c.label << ": " << (m.reached ? "reached" : "not reached")
              << " H=" << m.harmonics << " " << m.test << " true " << m.true_error << " (" << m.seconds << " s)\n";
    if (!m.reached) continue;
    ++reached;
    if (!m.exact) continue;
    ++measured;
    if (ratio <= 1.0) ++within;
    if (ratio <= 1.5) ++within_15;
    if (ratio > worst) {
      worst = ratio;
      worst_case = c.file + " ω = " + number(c.omega) + " " + c.label;
    }
  }
  md << "\ncases " << count << ", reached " << reached << ", of which measured against the exact orbit " << measured
     << ": true error <= TOL in " << within << " (" << number(measured ? 100.0 * within / measured : 0.0, 3)
     << " %), <= 1.5 TOL in " << within_15 << " (" << number(measured ? 100.0 * within_15 / measured : 0.0, 3)
     << " %); worst true error ÷ TOL " << number(worst, 3) << " (" << worst_case << "); " << number(seconds, 3)
     << " s in all\n";
  if (!bias.empty()) {
    std::sort(bias.begin(), bias.end());
    auto quantile = [&](double q) { return bias[std::min(bias.size() - 1, static_cast<size_t>(q * bias.size()))]; };
    md << "\nbias of the estimate (true error ÷ estimate) on the " << bias.size()
       << " rungs tested by the exact orbit below the last: median " << number(quantile(0.5), 3) << ", 90 % "
       << number(quantile(0.9), 3) << ", 95 % " << number(quantile(0.95), 3) << ", max " << number(bias.back(), 3)
       << "; above the safety factor " << o.safety_factor << ": "
       << std::count_if(bias.begin(), bias.end(), [&](double b) { return b > o.safety_factor; }) << "\n";
  }
  return md.str();
}

}  // namespace eqhb::bench
