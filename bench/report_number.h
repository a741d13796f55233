// A figure in the benchmark's Markdown tables: `digits` significant digits;
// a figure that does not exist (NaN) as `missing` when one is given.
#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace eqhb::bench {

inline std::string reportNumber(double x, int digits = 3, const char* missing = nullptr) {
  if (missing != nullptr && std::isnan(x)) return missing;
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

}  // namespace eqhb::bench
