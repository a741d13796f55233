// The default path by backend name, for the CLI, Python and the benchmark:
// the fallback chain of a solve (continuation/fallback_chain.h) with the
// backends it names made here and owned by it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "eqhb/continuation/fallback_chain.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// The backend tried last by default: Ipopt's least-squares form where built
// (the one backend that solves cubic at ω = 0.8 from rest), else Ceres'
// Levenberg–Marquardt, else the Newton dogleg; never `primary` itself.
std::string defaultBackupSolver(const std::string& primary);

// The backend the default path tries on the full system after the backup:
// Ceres' Levenberg-Marquardt where built (the damper above its peak at
// H >= 25 converges only there), none when it is `primary` itself.
std::string defaultFullSystemSolver(const std::string& primary);

class OwnedFallbackChain {
 public:
  // "default": cold, full, condensed, defaultBackupSolver(primary),
  // full:defaultFullSystemSolver(primary), forcing; "none"; or steps
  // "cold,full,NAME,..." (FallbackChain::parse). Throws InputError naming
  // `field` for an unknown step or backend.
  OwnedFallbackChain(const std::string& text, const std::string& primary, const std::string& field);
  const FallbackChain& chain() const { return chain_; }

 private:
  std::vector<std::unique_ptr<Solver>> owned_;
  FallbackChain chain_;
};

}  // namespace eqhb
