// A Solver whose registry name and description are fixed when it is made:
// each backend states them once, as the variant it was made for.
#pragma once

#include <string>

#include "eqhb/solvers/solver.h"

namespace eqhb {

// A backend's registry name (SolverChoice::solver) and one-line description.
struct SolverVariant {
  const char* name;
  const char* description;
};

class NamedSolver : public Solver {
 public:
  std::string name() const override { return name_; }
  std::string description() const override { return description_; }

 protected:
  explicit NamedSolver(const SolverVariant& variant) : name_(variant.name), description_(variant.description) {}

 private:
  std::string name_;
  std::string description_;
};

}  // namespace eqhb
