#include "eqhb/studies/study_scheduler.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>

namespace eqhb {

std::vector<int> samplesToCompute(const std::vector<int>& pending, const StudySettings& settings) {
  if (settings.mode != StudyMode::kPeak) return pending;
  std::vector<int> sorted = pending, ids;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const int block_start = sorted[i] / kWarmChain * kWarmChain;
    const bool first_of_block = i == 0 || sorted[i - 1] < block_start;
    for (int id = first_of_block ? block_start : sorted[i - 1] + 1; id <= sorted[i]; ++id) ids.push_back(id);
  }
  return ids;
}

GuidedScheduler::GuidedScheduler(std::vector<int> pending, int workers) : workers_(std::max(1, workers)) {
  std::sort(pending.begin(), pending.end());
  for (std::size_t i = 0; i < pending.size(); ++i) {
    if (i == 0 || pending[i] / kWarmChain != pending[i - 1] / kWarmChain) blocks_.emplace_back();
    blocks_.back().push_back(pending[i]);
  }
}

std::vector<int> GuidedScheduler::next() {
  const std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t remaining = blocks_.size() - position_;
  const std::size_t run = std::min(remaining, std::max<std::size_t>(1, remaining / (2 * workers_)));
  std::vector<int> ids;
  for (std::size_t b = position_; b < position_ + run; ++b) ids.insert(ids.end(), blocks_[b].begin(), blocks_[b].end());
  position_ += run;
  return ids;
}

void runStudyOnThreads(const StudySettings& settings, const std::vector<int>& pending, int threads,
                       const std::function<void(const SampleResult&)>& finished) {
  threads = std::max(1, std::min<int>(threads, static_cast<int>(pending.size())));
  GuidedScheduler scheduler(pending, threads);
  std::exception_ptr failure;
  std::mutex failure_mutex;
  std::atomic<bool> stop{false};
  auto work = [&](int worker) {
    try {
      SampleWorker sampler(settings, worker);
      for (auto ids = scheduler.next(); !ids.empty() && !stop; ids = scheduler.next())
        for (std::size_t i = 0; i < ids.size() && !stop; ++i) finished(sampler.run(ids[i]));
    } catch (...) {  // e.g. the journal cannot be written: every thread stops after its sample
      stop = true;
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  if (threads == 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(work, t);
    for (auto& t : pool) t.join();
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace eqhb
