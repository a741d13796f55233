#include "eqhb/scenes/toml_number.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace eqhb {

std::string tomlLiteral(const toml::value& value) {
  const toml::source_location where = value.location();
  const std::string& line = where.line_str();
  if (where.column() < 1 || where.column() - 1 >= line.size()) return "";
  return line.substr(where.column() - 1, where.region());
}

std::string floatRangeProblem(const toml::value& value) {
  if (!value.is_floating()) return "";
  std::string literal = tomlLiteral(value);
  literal.erase(std::remove(literal.begin(), literal.end(), '_'), literal.end());  // 1_000.0
  if (literal.empty()) return "";
  errno = 0;
  char* end = nullptr;
  const double parsed = std::strtod(literal.c_str(), &end);
  if (end == literal.c_str() || errno != ERANGE) return "";
  // ERANGE also flags subnormal results, which keep a (reduced) precision.
  if (parsed == 0.0)
    return "underflows to 0; not representable (the smallest positive double is about 4.9e-324)";
  if (std::isinf(parsed)) return "overflows; not representable (the largest double is about 1.8e308)";
  return "";
}

}  // namespace eqhb
