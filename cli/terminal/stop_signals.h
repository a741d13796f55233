// SIGINT and SIGTERM while a long command runs (a sweep): the first asks it
// to stop between two points and write what it has found (the curve, its
// stop reason, exit status 1); the handler is then reset, so a second signal
// ends the process at once as it would have without one.
#pragma once

#include <atomic>

namespace eqhb::cli {

class StopOnSignals {
 public:
  StopOnSignals();   // installs the handler for SIGINT and SIGTERM
  ~StopOnSignals();  // puts the previous handlers back
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

  // Set once a signal has come; read between the command's steps.
  const std::atomic<bool>* requested() const;
};

}  // namespace eqhb::cli
