// Dynamic distribution of a study's pending samples over workers (threads
// of one process, or MPI ranks). Guided self-scheduling over the warm-start
// blocks of the plan (kWarmChain samples, study_plan.h): a worker asking for
// work gets a run of whole consecutive blocks, about remaining / (2 · workers)
// of them — long runs first, single blocks near the end (balance, since
// samples differ in cost). Never splitting a block keeps every sample's
// start independent of the number of workers.
#pragma once

#include <functional>
#include <mutex>
#include <vector>

#include "eqhb/studies/study_sample.h"

namespace eqhb {

// The samples to compute so that every pending one starts from the state it
// has in an uninterrupted study. --peak: a block cut by a kill is computed
// again from its first sample up to its last pending one (the samples
// already in the journal are computed only to rebuild the warm starts; the
// caller does not write them twice), since a cold start in mid-block can
// follow other resonances. --sweep samples never start warm: `pending`.
std::vector<int> samplesToCompute(const std::vector<int>& pending, const StudySettings& settings);

class GuidedScheduler {
 public:
  GuidedScheduler(std::vector<int> pending, int workers);
  // The next run of sample ids (empty when everything is handed out).
  std::vector<int> next();

 private:
  std::vector<std::vector<int>> blocks_;  // pending samples, grouped by block
  std::size_t position_ = 0;
  int workers_;
  std::mutex mutex_;
};

// Computes `pending` on `threads` threads (>= 1), each with its own solver
// and warm-start state; `finished` is called for each sample as it
// completes, from the thread that computed it (it must be thread-safe).
// The first exception (from `finished` or a sample) stops every thread once
// its current sample is done, and is rethrown here.
void runStudyOnThreads(const StudySettings& settings, const std::vector<int>& pending, int threads,
                       const std::function<void(const SampleResult&)>& finished);

}  // namespace eqhb
