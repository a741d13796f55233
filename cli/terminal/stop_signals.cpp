#include "stop_signals.h"

#include <csignal>

namespace eqhb::cli {

namespace {

// Lock-free, so that setting it from a handler is async-signal-safe.
std::atomic<bool> g_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler may only set a lock-free flag");

struct sigaction g_previous_int, g_previous_term;

extern "C" void requestStop(int) { g_requested.store(true, std::memory_order_relaxed); }

}  // namespace

StopOnSignals::StopOnSignals() {
  g_requested.store(false);
  struct sigaction action = {};
  action.sa_handler = requestStop;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // the second signal takes the default action
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

StopOnSignals::~StopOnSignals() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

const std::atomic<bool>* StopOnSignals::requested() const { return &g_requested; }

}  // namespace eqhb::cli
