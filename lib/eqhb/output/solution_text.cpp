#include "eqhb/output/solution_text.h"

#include <map>
#include <sstream>

#include "eqhb/error.h"
#include "eqhb/output/invariant_meanings.h"
#include "eqhb/output/solution_json.h"
#include "eqhb/scenes/dof_choice.h"

namespace eqhb::output {

namespace {

void writeColdStart(std::ostream& out, const ColdStartReport& cold) {
  if (!cold.used) return;
  out << "cold start: coarse harmonic balance at H = " << cold.harmonics << ", N = " << cold.samples << ", "
      << (cold.coarse.converged() ? "converged" : "NOT converged (started from zero)") << " in "
      << cold.coarse.iterations << " iterations, " << cold.coarse.residual_evaluations << " residual and "
      << cold.coarse.jacobian_evaluations << " Jacobian evaluations\n";
  if (cold.retried_from_zero)
    out << "  the solve from it stopped (" << terminationName(cold.first_attempt.termination) << " after "
        << cold.first_attempt.iterations << " iterations); solved again from zero (above)\n";
}

void writeLinearAlgebra(std::ostream& out, const app::Solution& s) {
  const app::LinearAlgebraReport& la = s.linear_algebra;
  out << "linear algebra: " << (la.sparse_solver ? "sparse" : "dense");
  if (la.condensation)
    out << ", A_k factored " << (la.sparse_factors ? "sparse (UMFPACK)" : "dense") << " (" << la.factor_mib
        << " MiB of factors)";
  out << "; set-up " << s.run.setup_seconds << " s, peak RSS " << la.peak_rss_mib << " MiB\n";
  if (s.run.times.size() > 1)
    out << "median time over " << s.run.times.size() << " solves: " << s.run.medianSeconds() << " s\n";
}

// Which test decided the accuracy target, with its value and, where the
// estimate stood in for the exact orbit, why.
std::string accuracyTestLine(const AccuracyChoice& c) {
  if (!c.tested()) return "no rung was tested";
  std::ostringstream line;
  if (c.test == AccuracyTest::kExactOrbit)
    line << "tested against the exact orbit (shooting): relative error of max|x| " << c.error;
  else
    line << "tested by the estimate: " << c.estimate.max_abs << " x safety factor " << c.safety_factor << " = "
         << c.error << (c.test_note.empty() ? "" : " (no exact orbit: " + c.test_note + ")");
  return line.str();
}

void writeStability(std::ostream& out, const HillResult& hill) {
  if (!hill.failure.empty()) {
    out << "stability: not computed (" << hill.failure << ")\n";
    return;
  }
  out << "stability: " << (hill.stable ? "stable" : "UNSTABLE") << ", spectral radius " << hill.spectral_radius
      << " (" << (hill.method == "hill" ? "Hill, " + std::to_string(hill.pencil_size) + " unknowns"
                  : hill.method == "shooting" ? std::string("the exact orbit's multipliers, from shooting")
                                              : hill.method)
      << (hill.method == "shooting" ? std::string() : ", " + formatNumber(hill.seconds) + " s")
      << "); leading multipliers:";
  for (size_t i = 0; i < hill.exponents.size() && i < 8; ++i) {
    const auto& e = hill.exponents[i];
    out << " " << e.multiplier.real() << (e.multiplier.imag() < 0 ? "" : "+") << e.multiplier.imag() << "i";
  }
  out << "\n";
}

// One line on the static state under the scene's preload: who found it and
// how many elements each state holds.
void writeStaticState(std::ostream& out, const StaticContactState& state) {
  std::map<std::string, int> counts;
  for (const auto& status : state.status)
    if (status) ++counts[staticStateName(status->state)];
  out << "static state under the preload: " << state.solver << " in " << state.result.iterations << " iterations";
  for (const std::string& failed : state.failed) out << " (after " << failed << ")";
  for (const auto& [name, count] : counts) out << ", " << count << " " << name;
  out << "\n";
}

}  // namespace

void writeSolutionText(std::ostream& out, const app::Solution& s) {
  const app::HbRun& run = s.run;
  const HbModel& model = s.model();
  out << run.scene.name << " at omega = " << model.omega << ", H = " << model.basis.count() << " ("
      << HarmonicSet::kindName(model.basis.kind()) << "), N = " << model.samples << ", "
      << (run.system->condensed() ? "condensed" : "full") << " system of " << run.system->size() << " unknowns\n"
      << run.result.summary() << "\n";
  if (run.scene.at_rest) writeStaticState(out, *run.scene.at_rest);
  writeColdStart(out, run.cold_start);
  if (!run.fallback.attempts.empty())
    out << "fallback: " << describeFallbacks(run.fallback)
        << (run.fallback.taken.empty() ? "; none converged" : "; the result above is " + run.fallback.taken + "'s")
        << "\n";
  writeLinearAlgebra(out, s);
  // The DOFs the scene's output choice shows (scenes/dof_choice.h), every law force.
  if (const std::string note = shownDofsNote(model, run.scene.output); !note.empty()) out << "  " << note << "\n";
  for (int dof : run.scene.output.shown)
    out << "  max|" << s.summary.displacements[dof].label << "| = " << s.summary.displacements[dof].max_abs << "\n";
  for (const auto& c : s.summary.forces) out << "  max|" << c.label << "| = " << c.max_abs << "\n";
  if (const auto& e = s.error_estimate)
    out << "estimated relative error of max|x|: " << e->max_abs << " (solve at H = " << e->refined_harmonics
        << (e->available ? "" : ", which did NOT converge") << ")\n";
  if (const auto& r = s.refinement)
    out << "refined by shooting: " << (r->converged ? "exact periodic orbit" : "NOT converged: " + r->failure)
        << ", period residual " << r->orbit.period_residual << " after " << r->orbit.iterations << " Newton steps, "
        << r->seconds << " s (max|x| above: the orbit's; coefficients: its truncation on H = " << r->basis.count()
        << ")" << (r->orbit.events.count("impact") ? "; impacts with restitution e = " + formatNumber(s.restitution) : "")
        << "\n";
  if (const auto& a = s.accuracy)
    out << "--accuracy " << a->tolerance << ": " << (a->choice.reached ? "reached" : "NOT reached") << " at H = "
        << model.basis.count() << ", N = " << model.samples
        << ", rho = " << rhoJson(a->candidates.scene_rho, a->rhoFactor()).dump() << " in " << a->choice.seconds
        << " s of solves\n"
        << "  " << accuracyTestLine(a->choice) << "\n";
  for (const auto& report : s.invariants) {
    out << "  law " << report.law + 1 << " (" << report.type << ") worst violations:";
    for (const auto& [name, value] : report.violations) out << " " << name << " " << value;
    out << "\n";
  }
  writeInvariantMeanings(out, s.invariants);
  if (s.stability) writeStability(out, *s.stability);
}

}  // namespace eqhb::output
