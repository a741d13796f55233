// Prints the Moré–Garbow–Hillstrom comparison of the own dogleg and MINPACK
// hybrj (Markdown), for the closing figures and the report.
#include <iostream>

#include "mgh/mgh_problems.h"
#include "eqhb/backends/registry.h"

int main() {
  auto own = eqhb::makeSolver("dogleg");
  auto reference = eqhb::makeSolver("minpack");
  const auto rows = eqhb::mgh::compare(*own, *reference, eqhb::mgh::standardCases());
  std::cout << eqhb::mgh::markdownTable(rows);
  int regressions = 0;
  for (const auto& r : rows) regressions += r.reference.solved && !r.own.solved;
  return regressions == 0 ? 0 : 1;
}
