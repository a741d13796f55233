#include "eqhb/continuation/fallback_chain.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <sstream>

#include "eqhb/continuation/omega_fallback.h"
#include "eqhb/continuation/solve_series.h"
#include "eqhb/error.h"
#include "eqhb/preload/operating_point.h"

namespace eqhb {

namespace {

constexpr const char* kCold = "cold";
constexpr const char* kFull = "full";
constexpr const char* kCondensed = "condensed";
constexpr const char* kForcing = "forcing";
constexpr const char* kOmega = "omega";
// "full:NAME": the backend NAME on the full system.
constexpr const char* kFullWith = "full:";
// What a step may be, for the messages that refuse one.
constexpr const char* kStepKinds = "cold, full, condensed, forcing, omega, a backend name or full:NAME";

bool isFullWith(const std::string& step) { return step.rfind(kFullWith, 0) == 0; }

// The forcing homotopy: the first fraction of the dynamic loads solved cold,
// the first step up, the smallest step before it gives up, and the most
// solves it may take (each a few iterations where the steps succeed).
constexpr double kForcingStart = 0.25, kForcingFirstStep = 0.25, kForcingSmallestStep = 1.0 / 256.0;
constexpr int kForcingMostSolves = 40;

// A backend step's most iterations: its rescues take a few dozen (Ceres'
// LM on the damper above its peak: 13 from rest), where its 1000 on a
// stalled full system cost minutes (a Jenkins element against a wall at
// ω = 0.7, H = 80: 118 s of a 128 s solve, which the omega step then
// converged in 3 s).
constexpr int kBackendStepIterations = 100;

// `options` for a chain step's `backend`: the backend-specific settings
// (`--option NAME=VALUE`) are the failed solve's backend's; another backend
// would refuse them (ipopt-ls: invalid_options, the step lost) and runs on
// its own defaults.
SolverOptions forBackend(const Solver& backend, const Solver& failed_with, SolverOptions options) {
  if (backend.name() != failed_with.name()) options.backend.clear();
  options.max_iterations = std::min(options.max_iterations, kBackendStepIterations);
  return options;
}

// `model` on the full system from its cold start; `full` gets the answer's [x; λ].
SolverResult solveFullSystemAt(const HbModel& model, Solver& solver, const SolverOptions& options,
                               const Eigen::VectorXd& rest_full, Eigen::VectorXd* full) {
  auto system = makeHbSystem(model, false, options.linear_algebra);
  SolverResult result = solveCold(solver, *system, options, rest_full);
  *full = system->fullCoefficients(result.solution);
  return result;
}

// The same ω on the full system, its answer mapped back to `condensed`'s unknowns.
SolverResult solveOnFullSystem(Solver& solver, HbSystem& condensed, const SolverOptions& options,
                               const Eigen::VectorXd& rest_full) {
  Eigen::VectorXd full;
  SolverResult result = solveFullSystemAt(condensed.model(), solver, options, rest_full, &full);
  result.solution = condensed.fromFullCoefficients(full);
  return result;
}

// The same ω on the condensed system from its cold start (the full one
// failed), its answer then polished on `full` by the same backend from the
// mapped point: the condensed residual converging does not make the full
// residual, in its own scales, converge too, and the result must be one of
// `full`'s solves. Iterations and evaluations are both solves' together.
SolverResult solveOnCondensedSystem(Solver& solver, HbSystem& full, const SolverOptions& options,
                                    const Eigen::VectorXd& rest_full) {
  auto condensed = makeHbSystem(full.model(), true, options.linear_algebra);
  const SolverResult reduced = solveCold(solver, *condensed, options, rest_full);
  if (!reduced.converged()) return reduced;
  SolverOptions polish = options;
  if (options.time_limit > 0.0) polish.time_limit = std::max(options.time_limit - reduced.seconds, 1e-3 * options.time_limit);
  SolverResult result = solver.solve(full, full.fromFullCoefficients(condensed->fullCoefficients(reduced.solution)), polish);
  result.iterations += reduced.iterations;
  result.residual_evaluations += reduced.residual_evaluations;
  result.jacobian_evaluations += reduced.jacobian_evaluations;
  result.seconds += reduced.seconds;
  return result;
}

// `model` with its dynamic loads (harmonic >= 1) times `fraction`; the
// static ones (a preload) stay whole.
HbModel withDynamicLoadsScaled(HbModel model, double fraction) {
  for (HarmonicLoad& load : model.structure.loads)
    if (load.harmonic > 0) {
      load.cos_amplitude *= fraction;
      load.sin_amplitude *= fraction;
    }
  return model;
}

// A homotopy in the forcing: the dynamic loads scaled to kForcingStart and
// solved from the cold start, then raised to the whole with each solve
// starting at the last, the step doubled after a success and halved after a
// failure. Small loads barely touch a wall or slip a friction contact, so
// the first solve is nearly linear; each step after it moves the contact
// instants a little. Measured: contact at ω = 0.5, H = 40, where every
// backend stalls from rest and from the coarse start at a local minimum of
// ‖g‖ (0.013), converges through 0.25, 0.5, 1 in a few iterations each.
// Iterations and evaluations are all the solves' together.
SolverResult solveByForcingHomotopy(Solver& solver, HbSystem& system, const SolverOptions& options,
                                    const Eigen::VectorXd& rest_full) {
  SolveSeries series(options);
  SolverResult last;
  last.termination = Termination::kNotProgressing;
  double reached = 0.0, step = kForcingStart;
  bool whole = false;  // the whole load solved: `last` is this system's answer
  Eigen::VectorXd full = rest_full;  // the last converged [x; λ]; empty: the cold start
  for (int solves = 0; solves < kForcingMostSolves && step >= kForcingSmallestStep; ++solves) {
    const double fraction = std::min(1.0, reached + step);
    SolverResult r;
    Eigen::VectorXd answer;
    if (fraction == 1.0) {  // the system itself, its answer in its own unknowns
      r = full.size() ? solver.solve(system, system.fromFullCoefficients(full), series.next())
                      : solveCold(solver, system, series.next(), rest_full);
      if (r.converged()) answer = system.fullCoefficients(r.solution);
    } else {
      auto scaled = makeHbSystem(withDynamicLoadsScaled(system.model(), fraction), system.condensed(),
                                 options.linear_algebra);
      r = reached > 0.0 ? solver.solve(*scaled, scaled->fromFullCoefficients(full), series.next())
                        : solveCold(solver, *scaled, series.next(), rest_full);
      if (r.converged()) answer = scaled->fullCoefficients(r.solution);
    }
    series.count(r);
    last = r;
    if (r.termination == Termination::kTimeLimit || r.termination == Termination::kInvalidOptions) break;
    if (!r.converged()) {
      if (reached == 0.0) break;  // no foothold: the smallest load is as hard as the whole
      step /= 2.0;
      continue;
    }
    if (fraction == 1.0) {
      whole = true;
      break;
    }
    full = answer;
    reached = fraction;
    step *= 2.0;
  }
  SolverResult out = series.total(last);
  // A converged solve of a fraction below 1 is not an answer to this system.
  if (!whole && out.converged()) {
    out.termination = Termination::kIterationLimit;
    out.native_message = "the forcing homotopy reached " + formatNumber(reached) + " of the loads in " +
                         std::to_string(kForcingMostSolves) + " solves";
  }
  return out;
}

}  // namespace

FallbackChain FallbackChain::standard(Solver* backup, Solver* full_backup) {
  FallbackChain chain;
  chain.steps = {kCold, kFull, kCondensed};
  chain.solvers = {nullptr, nullptr, nullptr};
  if (backup) {
    chain.steps.push_back(backup->name());
    chain.solvers.push_back(backup);
  }
  // After the backup: it only runs where every step before it failed, so
  // the points those steps rescued cost what they did.
  if (full_backup) {
    chain.steps.push_back(kFullWith + full_backup->name());
    chain.solvers.push_back(full_backup);
  }
  // Last: the forcing homotopy takes several solves, and the steps before it
  // rescue every point they rescued before it existed at the same cost.
  chain.steps.push_back(kForcing);
  chain.solvers.push_back(nullptr);
  // After it: continuation in ω walks a dozen solves or more, and every step
  // before it keeps the points it rescued, at the same cost (the solves that
  // converged before it existed are the same solves).
  chain.steps.push_back(kOmega);
  chain.solvers.push_back(nullptr);
  return chain;
}

namespace {

// The chain's steps (with their backends) for which `keep` holds, in order.
FallbackChain keepSteps(const FallbackChain& from, const std::function<bool(const std::string&)>& keep) {
  FallbackChain chain = from;
  chain.steps.clear();
  chain.solvers.clear();
  for (size_t i = 0; i < from.steps.size(); ++i)
    if (keep(from.steps[i])) {
      chain.steps.push_back(from.steps[i]);
      chain.solvers.push_back(from.solvers[i]);
    }
  return chain;
}

}  // namespace

FallbackChain FallbackChain::forWarmPoints() const {
  return keepSteps(*this, [](const std::string& s) { return s != kForcing && s != kOmega && !isFullWith(s); });
}

FallbackChain FallbackChain::withoutOmegaContinuation() const {
  return keepSteps(*this, [](const std::string& s) { return s != kOmega; });
}

FallbackChain FallbackChain::withOwnBackendOnly() const {
  return keepSteps(*this, [](const std::string& s) { return s == kCold || s == kFull || s == kCondensed; });
}

FallbackChain FallbackChain::parse(const std::string& text, const std::string& field,
                                   const std::function<Solver*(const std::string&)>& solver_for) {
  FallbackChain chain;
  if (text == "none") return chain;
  std::stringstream list(text);
  for (std::string step; std::getline(list, step, ',');) {
    if (step.empty()) throwInputError(field, text, std::string("has an empty step (steps: ") + kStepKinds + ", comma-separated, or none)");
    if (std::find(chain.steps.begin(), chain.steps.end(), step) != chain.steps.end())
      throwInputError(field, text, "names " + step + " twice");
    Solver* backend = nullptr;
    if (step != kCold && step != kFull && step != kCondensed && step != kForcing && step != kOmega) {
      backend = solver_for(isFullWith(step) ? step.substr(std::string(kFullWith).size()) : step);
      if (!backend)
        throwInputError(field, text, "has an unknown step " + step + " (steps: " + kStepKinds + ", or none)");
    }
    chain.steps.push_back(step);
    chain.solvers.push_back(backend);
  }
  if (chain.steps.empty() || text.back() == ',')
    throwInputError(field, text, std::string("has an empty step (steps: ") + kStepKinds + ", comma-separated, or none)");
  return chain;
}

SolverResult solveWithFallbacks(HbSystem& system, Solver& solver, const SolverOptions& options,
                                const SolverResult& failed, bool started_cold, const FallbackChain& chain,
                                FallbackReport* report) {
  FallbackReport local;
  FallbackReport& r = report ? *report : local;
  r = FallbackReport();
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&]() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // The time limit is the chain's whole: each step gets what is left.
  auto remaining = [&]() {
    SolverOptions o = options;
    if (options.time_limit > 0.0) o.time_limit = options.time_limit - elapsed();
    return o;
  };
  if (failed.termination == Termination::kInvalidOptions || failed.termination == Termination::kTimeLimit) return failed;
  // Under a preload every cold start begins about the static state, at this ω.
  const Eigen::VectorXd rest_full =
      chain.at_rest ? linearisedStart(system.model(), *chain.at_rest, remaining()) : Eigen::VectorXd();
  for (size_t i = 0; i < chain.steps.size(); ++i) {
    const std::string& step = chain.steps[i];
    if (step == kCold && started_cold) continue;        // the failed solve was this one
    if (step == kFull && !system.condensed()) continue;  // already on the full system
    if (step == kCondensed && system.condensed()) continue;
    // On the full system full:NAME is the step NAME: where the chain has both, one solve.
    if (isFullWith(step) && !system.condensed() &&
        std::find(chain.steps.begin(), chain.steps.end(), step.substr(std::string(kFullWith).size())) !=
            chain.steps.end())
      continue;
    if (options.time_limit > 0.0 && elapsed() >= options.time_limit) break;
    FallbackAttempt attempt{step, SolverResult(), ""};
    try {
      if (step == kCold) attempt.result = solveCold(solver, system, remaining(), rest_full);
      else if (step == kFull) attempt.result = solveOnFullSystem(solver, system, remaining(), rest_full);
      else if (step == kCondensed) attempt.result = solveOnCondensedSystem(solver, system, remaining(), rest_full);
      else if (step == kForcing) attempt.result = solveByForcingHomotopy(solver, system, remaining(), rest_full);
      else if (step == kOmega)
        attempt.result = solveByOmegaContinuation(solver, system, remaining(), chain.at_rest.get(), &attempt.note);
      else if (isFullWith(step) && system.condensed())
        attempt.result = solveOnFullSystem(*chain.solvers[i], system,
                                           forBackend(*chain.solvers[i], solver, remaining()), rest_full);
      else attempt.result = solveCold(*chain.solvers[i], system, forBackend(*chain.solvers[i], solver, remaining()),
                                      rest_full);
    } catch (const std::exception& e) {  // a singular A_k, a system too large for memory
      attempt.result.solver = step;
      attempt.result.termination = Termination::kBackendError;
      attempt.result.native_message = e.what();
    }
    r.attempts.push_back(attempt);
    if (attempt.result.converged()) {
      r.taken = step;
      r.seconds = elapsed();
      return attempt.result;
    }
  }
  r.seconds = elapsed();
  return failed;
}

SolverResult solveWhereCondensationIsSingular(const HbModel& model, double omega, Solver& solver,
                                              const SolverOptions& options, const FallbackChain& chain,
                                              Eigen::VectorXd* full, FallbackReport* report) {
  FallbackReport local;
  FallbackReport& r = report ? *report : local;
  r = FallbackReport();
  SolverResult result;
  result.termination = Termination::kBackendError;
  result.native_message = "the condensed system is singular at this omega and the fallbacks have no full step";
  if (std::find(chain.steps.begin(), chain.steps.end(), kFull) == chain.steps.end()) return result;
  const auto start = std::chrono::steady_clock::now();
  FallbackAttempt attempt{kFull, SolverResult(), ""};
  try {
    HbModel at = model;
    at.omega = omega;
    const Eigen::VectorXd rest_full =
        chain.at_rest ? linearisedStart(at, *chain.at_rest, options) : Eigen::VectorXd();
    attempt.result = solveFullSystemAt(at, solver, options, rest_full, full);
  } catch (const std::exception& e) {
    attempt.result.solver = solver.name();
    attempt.result.termination = Termination::kBackendError;
    attempt.result.native_message = e.what();
  }
  r.attempts.push_back(attempt);
  if (attempt.result.converged()) r.taken = kFull;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return attempt.result;
}

std::string describeFallbacks(const FallbackReport& report) {
  std::string out;
  for (const FallbackAttempt& a : report.attempts) {
    if (!out.empty()) out += ", ";
    out += a.step + " (" + a.result.solver + ": " + terminationName(a.result.termination) +
           (a.result.converged() ? "" : " after " + std::to_string(a.result.iterations) + " iterations") +
           (a.note.empty() ? "" : "; " + a.note) + ")";
  }
  return out.empty() ? "no fallback step applied" : out;
}

}  // namespace eqhb
