// One sample of a parameter study: the scene with the sample's overrides,
// solved for its resonance peak (PeakTracking) or its whole frequency
// response (sequential continuation), reported as one row.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "eqhb/solvers/solver.h"
#include "eqhb/studies/peak_tracking.h"
#include "eqhb/studies/study_plan.h"

namespace eqhb {

enum class StudyMode { kPeak, kSweep };

struct StudySettings {
  std::string scene_path;
  std::vector<std::string> overrides;  // applied to every sample before its own
  StudyPlan plan;
  StudyMode mode = StudyMode::kPeak;
  PeakOptions peak;          // range [from, to], DOF, condensed; also the sweep's range
  double sweep_step = 0.01;  // kSweep: grid step in ω
  std::string out_dir;       // the study folder (kSweep: one curve CSV per sample in curves/)
  int dofs = 0;              // of the scene; every sample must keep it
  // Each DOF's name in the CSV columns ("w3" on a beam, HbModel::dof_names);
  // empty: "x1".."xn".
  std::vector<std::string> dof_labels;
  // The DOFs (0-based) whose columns study.csv has, in order; empty: every
  // DOF (the journal always has every DOF, which study.json reports).
  std::vector<int> csv_dofs;
  SolverOptions solver_options;
  std::function<std::unique_ptr<Solver>()> make_solver;
  // Per worker, the fallback chain of its sweeps, owning its backends; empty
  // (or null returned): the sweeps' standard chain.
  std::function<std::shared_ptr<const FallbackChain>()> make_fallbacks;
};

struct SampleResult {
  int id = -1;
  std::vector<double> parameters;
  bool ok = false;
  std::string reason;  // why it failed
  std::string start;   // peak: warm / cold ...; sweep: "sweep"
  double omega = 0.0;  // of the peak (sweep: the largest grid point)
  std::vector<double> first_harmonic, max_abs;  // per DOF at the peak
  int peaks = 0;       // --peak: resonances followed
  int solves = 0, iterations = 0;
  double seconds = 0.0;
  int worker = 0;      // thread or rank that computed it
  std::string curve;   // kSweep: the curve file, relative to the study folder
};

// Computes samples one after another and keeps the last peaks: a sample that
// directly follows the previous one in study order and continues it
// (StudyPlan::continues) starts from its peaks; any other starts cold.
class SampleWorker {
 public:
  SampleWorker(const StudySettings& settings, int worker);
  // A sample that cannot be computed is a failed row; throws only IoError
  // (its curve file cannot be written).
  SampleResult run(int id);

 private:
  SampleResult compute(int id);
  const StudySettings& settings_;
  int worker_;
  std::unique_ptr<Solver> solver_;
  std::shared_ptr<const FallbackChain> fallbacks_;  // null: the standard chain
  int previous_id_ = -2;
  PeakState previous_peak_;
};

// The scene of sample `id` (base overrides then the sample's); throws
// InputError as loadScene.
std::vector<std::string> sampleOverrides(const StudySettings& settings, int id);

}  // namespace eqhb
