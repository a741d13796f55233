#include "bench_cases.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <sstream>

#include "case_verdict.h"
#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/references/time_integrator.h"
#include "eqhb/scenes/scene.h"

namespace eqhb::bench {

namespace {

double worstDisplacementError(const std::vector<ChannelError>& errors) {
  double worst = 0.0;
  for (const auto& e : errors)
    if (e.label[0] == 'x') worst = std::max(worst, e.relative_l2);
  return worst;
}

// Worst relative distance per DOF to the 4x-H solution, on the 4x-H basis
// (this solution padded with zeros).
double highHarmonicError(const HbModel& model, const Eigen::VectorXd& full, const Truth& truth) {
  const Eigen::VectorXd padded = transferCoefficients(model, truth.high_model, full);
  const int n = model.structure.dofs(), nb = truth.high_model.basis.size();
  // Per DOF, relative to the DOF's own size floored like the time
  // reference's channels (a DOF at rest is not divided by its noise).
  double largest = 0.0, worst = 0.0;
  for (int i = 0; i < n; ++i) largest = std::max(largest, truth.high.segment(i * nb, nb).norm());
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, (padded.segment(i * nb, nb) - truth.high.segment(i * nb, nb)).norm() /
                                std::max({truth.high.segment(i * nb, nb).norm(), kChannelFloor * largest, 1e-300}));
  return worst;
}

}  // namespace

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

Case runCase(const std::string& study, const std::filesystem::path& path, const std::vector<std::string>& set,
             const std::string& solver_name, bool condensed, int repeats, double time_limit, const Truth* truth) {
  const Scene scene = loadScene(path.string(), set);
  Case c;
  c.study = study;
  c.scene = scene.name;
  c.solver = solver_name;
  c.system = condensed ? "condensed" : "full";
  c.harmonics = scene.model.basis.count();
  std::unique_ptr<HbSystem> system;
  try {
    system = makeHbSystem(scene.model, condensed);
  } catch (const std::exception& e) {
    c.termination = "not_applicable";
    return c;
  }
  // The default path is the own dogleg followed, where it fails, by the
  // library's fallback chain (cold start, full system, a second backend):
  // what a user gets without choosing, timed as a whole.
  const bool default_path = solver_name == kDefaultPath;
  auto solver = makeSolver(default_path ? "dogleg" : solver_name);
  std::unique_ptr<OwnedFallbackChain> fallbacks;
  if (default_path) fallbacks = std::make_unique<OwnedFallbackChain>("default", solver->name(), "solver");
  SolverOptions options;
  options.time_limit = time_limit;
  std::vector<double> times;
  SolverResult r;
  double spent = 0.0;  // repeat for a stable median; slow cases are repeated less
  for (int i = 0; i < repeats && (i == 0 || spent < 1.0); ++i) {
    const auto start = std::chrono::steady_clock::now();
    r = solver->solve(*system, Eigen::VectorXd::Zero(system->size()), options);
    if (default_path && !r.converged() && r.termination != Termination::kInvalidOptions)
      r = solveWithFallbacks(*system, *solver, options, r, true, fallbacks->chain(), nullptr);
    const double seconds =
        default_path ? std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() : r.seconds;
    times.push_back(seconds);
    spent += seconds;
  }
  c.repeats = static_cast<int>(times.size());
  c.converged = r.converged();
  c.termination = terminationName(r.termination);
  c.iterations = r.iterations;
  c.residual_evaluations = r.residual_evaluations;
  c.jacobian_evaluations = r.jacobian_evaluations;
  c.residual_norm = r.final_norm;
  c.median_seconds = r.termination == Termination::kInvalidOptions ? NAN : median(times);
  if (c.converged && truth) {
    const Eigen::VectorXd full = system->fullCoefficients(r.solution);
    if (truth->exact) c.error_reference = worstRelativeL2(scene.model, full, *truth->exact);
    else if (truth->has_reference)
      c.error_reference = worstDisplacementError(compareWithReference(scene.model, full, truth->reference));
    if (truth->high.size()) c.error_high_h = highHarmonicError(scene.model, full, *truth);
    if (truth->exact && scene.model.basis.count() == truth->truncation_harmonics)
      c.truncation_error = truth->truncation_error;
  }
  return c;
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void setRatiosToDogleg(std::vector<Case>& cases) {
  for (Case& c : cases)
    for (const Case& d : cases)
      if (d.solver == "dogleg" && d.study == c.study && d.scene == c.scene && d.harmonics == c.harmonics &&
          d.form == c.form && d.system == c.system && d.median_seconds > 0)
        c.ratio_to_dogleg = c.median_seconds / d.median_seconds;
}

namespace {
// A case's verdict in a table: a converged answer that disagrees with the
// references is a failure, and says so.
std::string verdictCell(const Case& c) {
  switch (verdictOf(c)) {
    case Verdict::kSolved: return "yes";
    case Verdict::kUnchecked: return "converged (no reference)";
    case Verdict::kDisagrees: return "**no** (disagrees with the references)";
    case Verdict::kFailed: break;
  }
  return "**no** (" + c.termination + ")";
}
}  // namespace

std::string table(const std::vector<Case>& cases, const std::string& study) {
  std::ostringstream t;
  t << "| scene | H | form | system | solver | solved | iterations | f-evals | J-evals | ‖g‖ | median s | / dogleg | L2 err vs time ref | L2 err vs 4H |\n"
    << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Case& c : cases) {
    if (c.study != study) continue;
    t << "| " << c.scene << " | " << c.harmonics << " | " << c.form << " | " << c.system << " | " << c.solver << " | "
      << verdictCell(c) << " | " << c.iterations << " | "
      << c.residual_evaluations << " | " << c.jacobian_evaluations << " | " << number(c.residual_norm) << " | "
      << number(c.median_seconds) << " | " << number(c.ratio_to_dogleg) << " | " << number(c.error_reference)
      << " | " << number(c.error_high_h) << " |\n";
  }
  return t.str();
}

}  // namespace eqhb::bench
