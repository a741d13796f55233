// A study on MPI ranks (Open MPI; built only when CMake finds MPI).
//
// Rank 0 coordinates: it hands out runs of consecutive pending samples
// (GuidedScheduler over the K − 1 worker ranks) and appends every result
// row to the journal as it arrives, so that a killed job loses only the
// samples being computed. Only rank 0 writes the journal (it holds the
// folder's lock); workers write only their curve files (--sweep). Every
// rank checks that its launcher is alive before it writes (and rank 0
// while it waits), so that ranks orphaned by a killed mpirun stop. Ranks 1..K−1 compute runs with their own solver
// and warm starts, send each row as soon as it is done and ask for the next
// run. Messages: a request (empty), a run (sample ids), a row (text).
#pragma once

#include <vector>

#include "eqhb/studies/study_journal.h"
#include "eqhb/studies/study_sample.h"

namespace eqhb {

// True when an MPI launcher (mpirun, mpiexec, srun) started this process.
bool launchedByMpi();

// MPI_Init / MPI_Finalize.
class MpiEnvironment {
 public:
  MpiEnvironment();
  ~MpiEnvironment();
  MpiEnvironment(const MpiEnvironment&) = delete;
  MpiEnvironment& operator=(const MpiEnvironment&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Rank 0's decision, on every rank (MPI_Bcast).
  bool agree(bool ok_on_rank_0) const;
  // Stops every rank (MPI_Abort): a coordinator that cannot go on.
  [[noreturn]] void abort(int code) const;
  // Ends this process at once, without a word to the other ranks, if the
  // process that launched it (mpirun, its daemon, srun's step daemon) is
  // gone: a rank orphaned by a killed job stops before writing anything
  // more into the study folder, where a resubmitted job may already run.
  void exitIfOrphaned() const;

 private:
  int rank_ = 0, size_ = 1;
  int launcher_ = 0;  // parent process id at start
};

struct MpiStudyTraffic {
  long messages = 0;  // received by the coordinator
  long bytes = 0;
  double coordinator_busy_seconds = 0.0;  // handling messages (not waiting)
};

// Coordinator on rank 0 (journal and pending given), worker elsewhere
// (journal null). Needs size() >= 2. Returns on every rank when done.
MpiStudyTraffic runStudyOnMpi(const MpiEnvironment& mpi, const StudySettings& settings, StudyJournal* journal,
                              const std::vector<int>& pending);

}  // namespace eqhb
