#include "study_command.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "eqhb/app/study.h"
#include "eqhb/error.h"
#include "eqhb/io_error.h"
#include "eqhb/output/study_json.h"
#include "eqhb/studies/study_journal.h"
#include "eqhb/studies/study_scheduler.h"
#include "flag_names.h"
#include "hdf5_option.h"
#include "terminal/run_program.h"
#ifdef EQHB_WITH_MPI
#include "eqhb/studies/mpi_study.h"
#endif

namespace eqhb::cli {

void addStudyCommand(CLI::App& app, SolveArguments& s, StudyArguments& a) {
  auto* cmd = app.add_subcommand("study", "Parameter study: resonance peaks or frequency responses over a grid "
                                          "or a Latin hypercube of scene values");
  addSceneOptions(cmd, s.scene);
  addSolverOptions(cmd, s);
  cmd->add_option("--vary", a.study.vary, "PATH=FROM:TO:COUNT, PATH as for --set or A,B,... set together (repeat "
                                          "for a grid; with --lhs, PATH=FROM:TO)")
      ->required();
  cmd->add_option("--lhs", a.study.lhs, "Latin hypercube of N samples instead of the grid");
  cmd->add_option("--seed", a.study.seed, "Random seed of --lhs")->capture_default_str();
  auto* sweep = cmd->add_flag("--sweep", a.sweep, "Per sample: the frequency-response curve over [from, to]");
  auto* peak = cmd->add_flag("--peak", a.peak, "Per sample: the resonance peak, tracked from sample to sample");
  sweep->excludes(peak);
  cmd->add_option("--from", a.study.from, "Lowest frequency (default: the scene's sweep.from)");
  cmd->add_option("--to", a.study.to, "Highest frequency (default: the scene's sweep.to)");
  cmd->add_option("--step", a.study.step, "Frequency step of --sweep")->capture_default_str();
  cmd->add_option("--dof", a.study.dof,
                  "DOF whose first-harmonic amplitude defines the peak, by number from 1 or name (\"w60\" on a beam)")
      ->capture_default_str();
  cmd->add_option("--coarse-points", a.study.coarse_points, "Points of the coarse sweep that starts a peak cold")
      ->capture_default_str();
  cmd->add_option("--max-peaks", a.study.max_peaks, "Resonances (local maxima in [from, to]) followed at once")
      ->capture_default_str();
  addHdf5Option(cmd, a.hdf5, "the samples (parameters, peaks, amplitudes)");
  cmd->add_option("--chart", a.chart,
                  "Write the design chart: the peak of --dof against the last varied value, one curve per value of "
                  "the others, the smallest starred (PREFIX.png and PREFIX.svg, matplotlib)");
  cmd->add_option("--threads", a.study.threads, "Threads (default: every core; one per MPI rank under mpirun)");
  cmd->add_option("--out", a.study.out, "Study folder: study.csv, study.json, journal.csv, plan.txt (resumable)")
      ->required();
}

namespace {

app::StudyOptions studyOptions(const SolveArguments& s, const StudyArguments& a) {
  app::StudyOptions o = a.study;
  readSolverChoice(s, &o);
  o.mode = a.sweep ? "sweep" : "peak";
  return o;
}

// The name of the study's peak DOF, as study.csv's columns have it.
std::string dofName(const StudySettings& s) {
  const int dof = s.peak.dof;
  return static_cast<size_t>(dof) < s.dof_labels.size() ? s.dof_labels[dof] : std::to_string(dof + 1);
}

// The design chart of the study folder (plot_study.py, installed beside plot_curve.py).
void writeStudyChart(const app::StudyRun& run, const StudyArguments& a) {
  const std::vector<std::string> command = {python3(), findDataFile("plot_study.py"), run.setup.settings.out_dir,
                                            a.chart, "--dof", dofName(run.setup.settings), "--title",
                                            run.setup.scene_name};
  std::fflush(stdout);  // the plotter prints the table of the smallest peaks after the summary
  if (runProgram(command) != 0)
    throw std::runtime_error("--chart: plotting failed (needs " + command[0] + " with matplotlib)");
}

// study.json, the summary on stdout, the chart when asked; the exit code.
int finish(const app::StudyRun& run, const StudyArguments& a) {
  const std::string& out = run.setup.settings.out_dir;
  output::writeStudyJson(out + "/study.json", run);
  const bool peak = run.setup.settings.mode == StudyMode::kPeak;
  std::printf("%s: %d samples (%s), %d computed now on %s in %.3g s (%.3g samples/s), %d failed\n",
              run.setup.scene_name.c_str(), run.total, peak ? "peak" : "sweep", run.computed, run.how.c_str(),
              run.seconds, run.computed > 0 ? run.computed / run.seconds : 0.0, run.failed());
  for (const auto& [id, r] : run.rows)
    if (!r.ok) std::printf("  sample %d failed: %s\n", id, r.reason.c_str());
  std::printf("  %s/study.csv, %s/study.json\n", out.c_str(), out.c_str());
  if (!a.hdf5.empty()) {
    writeStudyHdf5File(a.hdf5, run);
    std::printf("  %s\n", a.hdf5.c_str());
  }
  if (!a.chart.empty()) {
    writeStudyChart(run, a);
    std::printf("  chart: %s.png, %s.svg\n", a.chart.c_str(), a.chart.c_str());
  }
  return run.succeeded() ? 0 : 1;
}

}  // namespace

#ifdef EQHB_WITH_MPI
namespace {

// Rank 0 keeps the journal and coordinates; the other ranks compute.
int runOnMpi(const MpiEnvironment& mpi, const app::StudySetup& setup, const StudyArguments& a) {
  const StudySettings& settings = setup.settings;
  std::unique_ptr<StudyJournal> journal;
  std::string error;
  int error_code = 2;
  if (mpi.rank() == 0) {
    try {
      journal = std::make_unique<StudyJournal>(settings.out_dir, settings, setup.plan_text);
    } catch (const IoError& e) {
      error = std::string("I/O error: ") + e.what();
      error_code = 3;
    } catch (const InputError& e) {
      error = std::string("error: ") + withFlagNames(e.what());
    } catch (const std::exception& e) {
      error = std::string("error: ") + e.what();
    }
  }
  if (!mpi.agree(error.empty())) {
    if (mpi.rank() == 0) std::fprintf(stderr, "eqhb: %s\n", error.c_str());
    return error_code;  // rank 0's is the one mpirun reports
  }
  const std::vector<int> pending = journal ? journal->pending() : std::vector<int>();
  const auto started = std::chrono::steady_clock::now();
  MpiStudyTraffic traffic;
  try {
    traffic = runStudyOnMpi(mpi, settings, journal.get(), samplesToCompute(pending, settings));
  } catch (const IoError& e) {  // the journal or a curve file cannot be written: every rank stops
    std::fprintf(stderr, "eqhb: I/O error on rank %d: %s\n", mpi.rank(), e.what());
    mpi.abort(3);
  } catch (const std::exception& e) {  // the coordinator cannot record results
    std::fprintf(stderr, "eqhb: error on rank %d: %s\n", mpi.rank(), e.what());
    mpi.abort(2);
  }
  if (mpi.rank() != 0) return 0;
  app::StudyRun run;
  run.setup = setup;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  journal->writeMerged();
  run.rows = journal->done();
  run.total = static_cast<int>(settings.plan.samples.size());
  run.computed = static_cast<int>(pending.size());
  run.how = std::to_string(mpi.size()) + " MPI ranks (" + std::to_string(mpi.size() - 1) + " workers)";
  const int code = finish(run, a);
  std::printf("  coordinator: %ld messages, %ld bytes, busy %.3g s\n", traffic.messages, traffic.bytes,
              traffic.coordinator_busy_seconds);
  return code;
}

}  // namespace
#endif

int runStudy(const SolveArguments& s, const StudyArguments& a) {
  if (!a.sweep && !a.peak) throwInputError("study", "(mode)", "give --peak or --sweep");
#ifdef EQHB_WITH_MPI
  std::unique_ptr<MpiEnvironment> mpi;
  if (launchedByMpi()) mpi = std::make_unique<MpiEnvironment>();
#endif
  const app::StudySetup setup = app::setupStudy(s.scene, studyOptions(s, a));
#ifdef EQHB_WITH_MPI
  if (mpi && mpi->size() > 1) return runOnMpi(*mpi, setup, a);
#endif
  const bool terminal = isatty(STDERR_FILENO);
  const app::StudyRun run = app::runStudy(setup, a.study.threads, [terminal](int done, int todo) {
    if (!terminal) return;
    std::fprintf(stderr, "\r  sample %d/%d done", done, todo);
    std::fflush(stderr);
  });
  if (terminal) std::fprintf(stderr, "\n");
  return finish(run, a);
}

}  // namespace eqhb::cli
