// A parameter study of a scene as every interface runs it (`eqhb study`,
// Python's eqhb.study): a grid or Latin hypercube over scene values, each
// sample's resonance peak or frequency response, computed on threads into a
// resumable study folder (studies/study_journal.h). Launched on MPI ranks,
// the eqhb command computes the same setup with studies/mpi_study.h.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/app/scene_settings.h"
#include "eqhb/app/solver_choice.h"
#include "eqhb/studies/study_sample.h"

namespace eqhb::app {

// Defaults are those of `eqhb study`. The backend, system, limits and the
// fallbacks after a failed point of a sample's sweeps (solver_choice.h), with:
struct StudyOptions : SolverChoice {
  // "PATH=FROM:TO:COUNT" per parameter (a grid), PATH as for a scene
  // override or "A,B,..." set together; with lhs "PATH=FROM:TO".
  std::vector<std::string> vary;
  std::optional<int> lhs;          // a Latin hypercube of this many samples instead of the grid
  unsigned long long seed = 1;     // of the Latin hypercube
  std::string mode;                // "peak" (the resonance peak, tracked) or "sweep" (the curve)
  std::optional<double> from, to;  // default: the scene's [sweep]
  double step = 0.01;              // sweep: the grid step in ω, in (0, to - from]
  // peak: the DOF whose first-harmonic amplitude peaks, by number from 1 or
  // name ("w60"; scenes/dof_choice.h)
  std::string dof = "1";
  int coarse_points = 41;          // peak: points of the coarse sweep that starts a peak cold
  int max_peaks = 4;               // peak: resonances followed at once
  int threads = 0;                 // 0: every core, in [0, 4096]
  std::string out;                 // the study folder: study.csv, study.json, journal.csv, plan.txt
};

// The study resolved against its scene, before any sample is computed.
struct StudySetup {
  StudySettings settings;
  std::string scene_name;
  std::string plan_text;  // plan.txt: what makes a folder this study's
};

// study.csv has the columns of the DOFs the scene's settings show (show,
// [output] dofs, else scenes/dof_choice.h's default), and of `dof` after
// them when not among those.
// Checks the options and the varied paths (a path usable at neither end of
// its range is one error, not a failed row per sample); throws InputError
// naming the option (vary, lhs, mode, from, to, step, dof, coarse_points,
// max_peaks, threads, solver) or the scene's field.
StudySetup setupStudy(const SceneSettings& scene, const StudyOptions& options);

struct StudyRun {
  StudySetup setup;
  std::map<int, SampleResult> rows;  // every sample in the folder, this run's and earlier runs'
  std::string how;                   // where it ran: "2 thread(s)"
  int total = 0;                     // samples of the plan
  int computed = 0;                  // samples computed by this run
  double seconds = 0.0;              // of this run
  int failed() const;
  // Every sample in the folder and none failed.
  bool succeeded() const;
};

// Computes the samples not yet in the folder on `threads` threads (0: every
// core) and writes the journal's merged study.csv (study.json is the
// writers', output/study_json.h); `finished(done, todo)` after each sample,
// from the thread that computed it. Throws IoError if the folder cannot be
// written, InputError if it holds another study.
StudyRun runStudy(const StudySetup& setup, int threads,
                  const std::function<void(int done, int todo)>& finished = nullptr);
StudyRun study(const SceneSettings& scene, const StudyOptions& options,
               const std::function<void(int done, int todo)>& finished = nullptr);

}  // namespace eqhb::app
