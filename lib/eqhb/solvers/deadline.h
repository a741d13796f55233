// A wall-clock limit on a whole run: the set-up of a system (assembly,
// symbolic and numeric factorisations) as well as its solves, so that
// `--time-limit` bounds what the user waits for, not only the iterations.
// Long phases check it between their steps (harmonics, laws, factorisations)
// and stop with TimeLimitReached saying where they were. A single library
// call (one UMFPACK factorisation) is not interrupted: a run passes its
// limit by at most the longest such call.
#pragma once

#include <chrono>
#include <stdexcept>
#include <string>

namespace eqhb {

// Thrown when a Deadline has passed; the message says during what.
class TimeLimitReached : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Deadline {
 public:
  Deadline() = default;  // no limit
  // `seconds` from now; 0 means no limit. Throws InputError unless finite and >= 0.
  explicit Deadline(double seconds);

  bool limited() const { return seconds_ > 0.0; }
  double seconds() const { return seconds_; }  // the limit given
  double elapsed() const;
  // Seconds left (<= 0 once passed); infinity without a limit.
  double remaining() const;
  bool passed() const { return limited() && remaining() <= 0.0; }
  // Throws TimeLimitReached "time limit of S s reached during WHERE (after E s)"
  // when passed.
  void check(const std::string& where) const;

 private:
  double seconds_ = 0.0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace eqhb
