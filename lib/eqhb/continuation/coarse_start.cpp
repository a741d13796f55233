#include "eqhb/continuation/coarse_start.h"

#include <algorithm>
#include <chrono>

#include "eqhb/harmonic_balance/hb_solution.h"

namespace eqhb {

namespace {
constexpr int kFewestFineHarmonics = 4;  // below, the coarse rung would be most of the fine one
}  // namespace

HbModel coarseModel(const HbModel& fine) {
  if (fine.basis.count() < kFewestFineHarmonics) return fine;
  HbModel coarse = fine;
  coarse.basis = HarmonicSet(fine.basis.kind(), (fine.basis.count() + 1) / 3);
  const int wanted = std::max(4 * coarse.basis.highest(), coarse.basis.minimumSamples());
  int samples = 8;
  while (samples < wanted) samples *= 2;
  coarse.samples = std::min(samples, fine.samples);
  return coarse;
}

CoarseStart::CoarseStart(const HbModel& fine, bool condensed, LinearAlgebra linear_algebra,
                         const Deadline& deadline)
    : coarse_(eqhb::coarseModel(fine)) {
  if (coarse_.basis.count() == fine.basis.count()) return;
  system_ = makeHbSystem(coarse_, condensed, linear_algebra, deadline);
  zero_coarse_ = Eigen::VectorXd::Zero(system_->size());
}

SolverResult CoarseStart::solve(Solver& solver, HbSystem& fine_system, const SolverOptions& options,
                                ColdStartReport* report, const Eigen::VectorXd& rest_full) {
  ColdStartReport local;
  ColdStartReport& r = report ? *report : local;
  r = ColdStartReport();
  const Eigen::VectorXd rest =
      rest_full.size() ? fine_system.fromFullCoefficients(rest_full) : Eigen::VectorXd::Zero(fine_system.size());
  if (!system_) return solver.solve(fine_system, rest, options);
  r.used = true;
  r.harmonics = coarse_.basis.count();
  r.samples = coarse_.samples;
  // --time-limit bounds the whole cold start: each later solve gets what is left.
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&]() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto remaining = [&]() {
    SolverOptions o = options;
    if (options.time_limit > 0.0) o.time_limit = std::max(options.time_limit - elapsed(), 1e-3 * options.time_limit);
    return o;
  };
  auto finish = [&](SolverResult result) {
    r.seconds = elapsed();
    return result;
  };
  r.coarse = solver.solve(*system_,
                          rest_full.size() ? system_->fromFullCoefficients(
                                                 transferCoefficients(fine_system.model(), coarse_, rest_full))
                                           : zero_coarse_,
                          options);
  // A coarse solve that did not converge is no better a start than zero.
  if (!r.coarse.converged()) return finish(solver.solve(fine_system, rest, remaining()));
  const Eigen::VectorXd fine_start = fine_system.fromFullCoefficients(
      transferCoefficients(coarse_, fine_system.model(), system_->fullCoefficients(r.coarse.solution)));
  SolverResult fine = solver.solve(fine_system, fine_start, remaining());
  if (fine.converged() || fine.termination == Termination::kInvalidOptions) return finish(fine);
  r.retried_from_zero = true;
  r.first_attempt = fine;
  return finish(solver.solve(fine_system, rest, remaining()));
}

}  // namespace eqhb
