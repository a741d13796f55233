#include "eqhb/studies/mpi_study.h"

#include <mpi.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "eqhb/studies/study_scheduler.h"

namespace eqhb {

namespace {
constexpr int kRequestTag = 1;  // worker -> coordinator: give me a run
constexpr int kRunTag = 2;      // coordinator -> worker: sample ids (none: stop)
constexpr int kRowTag = 3;      // worker -> coordinator: one result row
// The coordinator's latency when idle; far below a sample's cost.
constexpr std::chrono::microseconds kPollInterval(200);

void coordinate(const MpiEnvironment& mpi, StudyJournal& journal,
                const std::vector<int>& pending, MpiStudyTraffic* traffic) {
  GuidedScheduler scheduler(pending, mpi.size() - 1);
  int active = mpi.size() - 1;
  std::string text;
  while (active > 0) {
    // Poll with short sleeps: a blocking MPI_Probe spins in Open MPI and
    // would take a core from a worker on the same node.
    MPI_Status status;
    int arrived = 0;
    while (true) {
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
      if (arrived) break;
      mpi.exitIfOrphaned();
      std::this_thread::sleep_for(kPollInterval);
    }
    const auto started = std::chrono::steady_clock::now();
    int length = 0;
    MPI_Get_count(&status, MPI_CHAR, &length);
    text.resize(length);
    MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    ++traffic->messages;
    traffic->bytes += length;
    if (status.MPI_TAG == kRowTag) {
      mpi.exitIfOrphaned();
      journal.appendRow(text);
    } else {
      const std::vector<int> run = scheduler.next();
      MPI_Send(run.data(), static_cast<int>(run.size()), MPI_INT, status.MPI_SOURCE, kRunTag, MPI_COMM_WORLD);
      if (run.empty()) --active;
    }
    traffic->coordinator_busy_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
}

void work(const MpiEnvironment& mpi, const StudySettings& settings) {
  SampleWorker worker(settings, mpi.rank());
  std::vector<int> run;
  while (true) {
    MPI_Send(nullptr, 0, MPI_CHAR, 0, kRequestTag, MPI_COMM_WORLD);
    MPI_Status status;
    MPI_Probe(0, kRunTag, MPI_COMM_WORLD, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_INT, &count);
    run.resize(count);
    MPI_Recv(run.data(), count, MPI_INT, 0, kRunTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (run.empty()) return;
    for (int id : run) {
      mpi.exitIfOrphaned();  // before a --sweep sample writes its curve
      const std::string row = studyCsvRow(worker.run(id), settings.dofs);
      MPI_Send(row.data(), static_cast<int>(row.size()), MPI_CHAR, 0, kRowTag, MPI_COMM_WORLD);
    }
  }
}

}  // namespace

bool launchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

// Ipopt's sequential MUMPS (libdmumps_seq, libmumps_common_seq) exports
// stand-ins named MPI_Init, MPI_Comm_rank, MPI_Finalize and MPI_Wtime, which
// can win symbol resolution over Open MPI's; the profiling names (PMPI_*),
// which every MPI library provides, reach the real ones.
MpiEnvironment::MpiEnvironment() : launcher_(static_cast<int>(getppid())) {
  PMPI_Init(nullptr, nullptr);
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiEnvironment::~MpiEnvironment() { PMPI_Finalize(); }

bool MpiEnvironment::agree(bool ok_on_rank_0) const {
  int ok = ok_on_rank_0 ? 1 : 0;
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return ok != 0;
}

// A process whose parent dies is adopted by init or a subreaper: its
// parent id changes. (Cheap enough to ask before every row.)
void MpiEnvironment::exitIfOrphaned() const {
  if (static_cast<int>(getppid()) == launcher_) return;
  std::fprintf(stderr, "eqhb: rank %d: the MPI launcher (process %d) is gone: stopping without writing more\n", rank_,
               launcher_);
  std::_Exit(3);
}

void MpiEnvironment::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

MpiStudyTraffic runStudyOnMpi(const MpiEnvironment& mpi, const StudySettings& settings, StudyJournal* journal,
                              const std::vector<int>& pending) {
  MpiStudyTraffic traffic;
  if (mpi.rank() == 0)
    coordinate(mpi, *journal, pending, &traffic);
  else
    work(mpi, settings);
  return traffic;
}

}  // namespace eqhb
