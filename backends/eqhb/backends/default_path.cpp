#include "eqhb/backends/default_path.h"

#include "eqhb/backends/registry.h"

namespace eqhb {

std::string defaultBackupSolver(const std::string& primary) {
  const std::vector<SolverEntry> known = registeredSolvers();
  for (const char* candidate : {"ipopt-ls", "ceres-lm", "dogleg-newton", "dogleg"})
    for (const SolverEntry& entry : known)
      if (entry.name == candidate && entry.name != primary) return entry.name;
  return "";
}

std::string defaultFullSystemSolver(const std::string& primary) {
  if (primary == "ceres-lm") return "";  // the chain's "full" step is already that
  for (const SolverEntry& entry : registeredSolvers())
    if (entry.name == "ceres-lm") return entry.name;
  return "";
}

OwnedFallbackChain::OwnedFallbackChain(const std::string& text, const std::string& primary,
                                       const std::string& field) {
  auto solver_for = [this](const std::string& name) -> Solver* {
    for (const SolverEntry& entry : registeredSolvers())
      if (entry.name == name) {
        owned_.push_back(makeSolver(name));
        return owned_.back().get();
      }
    return nullptr;
  };
  if (text == "default") {
    const std::string backup = defaultBackupSolver(primary), full_backup = defaultFullSystemSolver(primary);
    chain_ = FallbackChain::standard(backup.empty() ? nullptr : solver_for(backup),
                                     full_backup.empty() ? nullptr : solver_for(full_backup));
  } else {
    chain_ = FallbackChain::parse(text, field, solver_for);
  }
}

}  // namespace eqhb
