#include "study_command.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <memory>
#include <mutex>
#include <thread>

#include "eqhb/backends/registry.h"
#include "eqhb/checked_file.h"
#include "eqhb/error.h"
#include "eqhb/io_error.h"
#include "eqhb/studies/study_journal.h"
#include "eqhb/studies/study_scheduler.h"
#ifdef EQHB_WITH_MPI
#include "eqhb/studies/mpi_study.h"
#endif

namespace eqhb::cli {

void addStudyCommand(CLI::App& app, SolveArguments& s, StudyArguments& a) {
  auto* cmd = app.add_subcommand("study", "Parameter study: resonance peaks or frequency responses over a grid "
                                          "or a Latin hypercube of scene values");
  addSceneOptions(cmd, s.scene);
  addSolverOptions(cmd, s);
  cmd->add_option("--vary", a.vary, "PATH=FROM:TO:COUNT, PATH as for --set or A,B,... set together (repeat "
                                    "for a grid; with --lhs, PATH=FROM:TO)")
      ->required();
  cmd->add_option("--lhs", a.lhs, "Latin hypercube of N samples instead of the grid");
  cmd->add_option("--seed", a.seed, "Random seed of --lhs")->capture_default_str();
  auto* sweep = cmd->add_flag("--sweep", a.sweep, "Per sample: the frequency-response curve over [from, to]");
  auto* peak = cmd->add_flag("--peak", a.peak, "Per sample: the resonance peak, tracked from sample to sample");
  sweep->excludes(peak);
  cmd->add_option("--from", a.from, "Lowest frequency (default: the scene's sweep.from)");
  cmd->add_option("--to", a.to, "Highest frequency (default: the scene's sweep.to)");
  cmd->add_option("--step", a.step, "Frequency step of --sweep")->capture_default_str();
  cmd->add_option("--dof", a.dof, "DOF whose first-harmonic amplitude defines the peak")->capture_default_str();
  cmd->add_option("--coarse-points", a.coarse_points, "Points of the coarse sweep that starts a peak cold")
      ->capture_default_str();
  cmd->add_option("--max-peaks", a.max_peaks, "Resonances (local maxima in [from, to]) followed at once")
      ->capture_default_str();
  cmd->add_option("--threads", a.threads, "Threads (default: every core; one per MPI rank under mpirun)");
  cmd->add_option("--out", a.out, "Study folder: study.csv, study.json, journal.csv, plan.txt (resumable)")
      ->required();
}

namespace {

nlohmann::json numberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void writeStudyJson(const std::string& path, const std::string& scene_name, const StudySettings& settings,
                    const std::map<int, SampleResult>& rows) {
  nlohmann::json j;
  j["scene"] = scene_name;
  j["mode"] = settings.mode == StudyMode::kPeak ? "peak" : "sweep";
  j["dof"] = settings.peak.dof;
  j["range"] = {settings.peak.from, settings.peak.to};
  j["parameters"] = nlohmann::json::array();
  for (const auto& p : settings.plan.parameters) j["parameters"].push_back(p.path);
  j["samples"] = nlohmann::json::array();
  for (const auto& [id, r] : rows) {
    nlohmann::json s;
    s["sample"] = id;
    for (std::size_t p = 0; p < r.parameters.size(); ++p)
      s["parameters"][settings.plan.parameters[p].path] = r.parameters[p];
    s["status"] = r.ok ? "ok" : "failed";
    if (!r.ok) s["reason"] = r.reason;
    s["start"] = r.start;
    s["peak_omega"] = r.ok ? numberOrNull(r.omega) : nullptr;
    s["first_harmonic"] = nlohmann::json::array();
    s["max_abs"] = nlohmann::json::array();
    for (double v : r.first_harmonic) s["first_harmonic"].push_back(numberOrNull(v));
    for (double v : r.max_abs) s["max_abs"].push_back(numberOrNull(v));
    if (settings.mode == StudyMode::kPeak) s["peaks"] = r.peaks;
    s["solves"] = r.solves;
    s["iterations"] = r.iterations;
    s["seconds"] = r.seconds;
    s["worker"] = r.worker;
    if (!r.curve.empty()) s["curve"] = r.curve;
    j["samples"].push_back(s);
  }
  writeFileChecked(path, j.dump(1) + "\n");
}

StudySettings studySettings(const SolveArguments& s, const StudyArguments& a, std::string* scene_name) {
  std::vector<VariedParameter> parameters;
  for (const auto& v : a.vary) parameters.push_back(parseVariedParameter(v, !a.lhs));
  StudySettings settings;
  settings.plan = a.lhs ? makeLatinHypercubePlan(parameters, *a.lhs, a.seed) : makeGridPlan(parameters);
  // The scene with the common overrides; the first sample's values checked
  // here so that a wrong path is one error, not a failed row per sample.
  const Scene scene = loadSceneWith(s.scene);
  *scene_name = scene.name;
  settings.scene_path = s.scene.path;
  settings.overrides = s.scene.overrides;
  if (s.scene.harmonics) settings.overrides.push_back("harmonic_balance.harmonics=" + std::to_string(*s.scene.harmonics));
  if (s.scene.samples) settings.overrides.push_back("harmonic_balance.samples=" + std::to_string(*s.scene.samples));
  if (s.scene.form || s.scene.rho) {
    if (s.scene.form) {
      const auto o = lawOverrides(scene.model, "form", *s.scene.form);
      settings.overrides.insert(settings.overrides.end(), o.begin(), o.end());
    }
    if (s.scene.rho) {
      const auto o = lawOverrides(scene.model, "rho", formatNumber(*s.scene.rho));
      settings.overrides.insert(settings.overrides.end(), o.begin(), o.end());
    }
  }
  settings.dofs = scene.model.structure.dofs();
  // A path that works at neither end of its range is a wrong path (or a
  // wrong range): one error. Values bad only somewhere are failed samples.
  for (const auto& p : parameters) {
    std::string why;
    for (double value : {p.from, p.to}) {
      try {
        std::vector<std::string> probe = settings.overrides;
        for (const auto& path : parameterPaths(p)) probe.push_back(path + "=" + formatNumber(value));
        loadScene(settings.scene_path, probe);
        why.clear();
        break;
      } catch (const InputError& e) {
        why = e.what();
      }
    }
    if (!why.empty()) throwInputError("--vary", p.path, "not a usable scene value: " + why);
  }
  settings.mode = a.sweep ? StudyMode::kSweep : StudyMode::kPeak;
  if (!a.from && !scene.sweep_from) throwInputError("--from", "(missing)", "the scene has no [sweep]: give --from and --to");
  settings.peak.from = a.from ? *a.from : *scene.sweep_from;
  settings.peak.to = a.to ? *a.to : *scene.sweep_to;
  settings.peak.dof = a.dof;
  settings.peak.coarse_points = a.coarse_points;
  settings.peak.max_peaks = a.max_peaks;
  settings.peak.condensed = !s.full;
  settings.peak.validate(settings.dofs);
  if (!(a.step > 0.0) || !std::isfinite(a.step) || a.step > settings.peak.to - settings.peak.from)
    throwInputError("--step", formatNumber(a.step), "must be in (0, to - from]");
  settings.sweep_step = a.step;
  if (a.threads < 0 || a.threads > 4096) throwInputError("--threads", std::to_string(a.threads), "must be in [0, 4096]");
  settings.solver_options = solverOptions(s);
  makeSolver(s.solver);  // an unknown name is an input error now, not per sample
  const std::string solver_name = s.solver;
  settings.make_solver = [solver_name] { return makeSolver(solver_name); };
  settings.out_dir = a.out;
  return settings;
}

// The summary on stdout and the merged files; the exit code.
int finish(StudyJournal& journal, const StudySettings& settings, const std::string& scene_name,
           const std::string& out, int computed, double seconds, const std::string& how) {
  journal.writeMerged();
  writeStudyJson(out + "/study.json", scene_name, settings, journal.done());
  int failed = 0;
  for (const auto& [id, r] : journal.done()) failed += r.ok ? 0 : 1;
  const int total = static_cast<int>(settings.plan.samples.size());
  std::printf("%s: %d samples (%s), %d computed now on %s in %.3g s (%.3g samples/s), %d failed\n",
              scene_name.c_str(), total, settings.mode == StudyMode::kPeak ? "peak" : "sweep", computed, how.c_str(),
              seconds, computed > 0 ? computed / seconds : 0.0, failed);
  for (const auto& [id, r] : journal.done())
    if (!r.ok) std::printf("  sample %d failed: %s\n", id, r.reason.c_str());
  std::printf("  %s/study.csv, %s/study.json\n", out.c_str(), out.c_str());
  const bool complete = static_cast<int>(journal.done().size()) == total;
  return complete && failed == 0 ? 0 : 1;
}

}  // namespace

#ifdef EQHB_WITH_MPI
namespace {

// Rank 0 keeps the journal and coordinates; the other ranks compute.
int runOnMpi(const MpiEnvironment& mpi, const SolveArguments& s, const StudyArguments& a,
             const StudySettings& settings, const std::string& scene_name) {
  std::unique_ptr<StudyJournal> journal;
  std::string error;
  int error_code = 2;
  if (mpi.rank() == 0) {
    try {
      journal = std::make_unique<StudyJournal>(a.out, settings, studyPlanText(settings, s.solver));
    } catch (const IoError& e) {
      error = std::string("I/O error: ") + e.what();
      error_code = 3;
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
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const int code = finish(*journal, settings, scene_name, a.out, static_cast<int>(pending.size()), seconds,
                          std::to_string(mpi.size()) + " MPI ranks (" + std::to_string(mpi.size() - 1) + " workers)");
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
  std::string scene_name;
  const StudySettings settings = studySettings(s, a, &scene_name);
#ifdef EQHB_WITH_MPI
  if (mpi && mpi->size() > 1) return runOnMpi(*mpi, s, a, settings, scene_name);
#endif
  StudyJournal journal(a.out, settings, studyPlanText(settings, s.solver));
  const std::vector<int> pending = journal.pending();
  const int threads = a.threads > 0 ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  const bool terminal = isatty(STDERR_FILENO);
  int finished = 0;
  std::mutex print;
  const auto started = std::chrono::steady_clock::now();
  const std::vector<int> to_compute = samplesToCompute(pending, settings);
  runStudyOnThreads(settings, to_compute, threads, [&](const SampleResult& r) {
    journal.append(r);  // locks
    if (terminal) {
      const std::lock_guard<std::mutex> lock(print);
      std::fprintf(stderr, "\r  sample %d/%zu done", ++finished, to_compute.size());
      std::fflush(stderr);
    }
  });
  if (terminal) std::fprintf(stderr, "\n");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const int used = std::max(1, std::min(threads, static_cast<int>(pending.size())));
  return finish(journal, settings, scene_name, a.out, static_cast<int>(pending.size()), seconds,
                std::to_string(used) + " thread(s)");
}

}  // namespace eqhb::cli
