// Error type for bad input: every message names the offending field, its value
// and the rule it breaks, so a user can fix a scene file or a flag without
// reading the source.
#pragma once

#include <stdexcept>
#include <string>

namespace eqhb {

class InputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Throws InputError("FIELD = VALUE: RULE").
[[noreturn]] void throwInputError(const std::string& field, const std::string& value,
                                  const std::string& rule);

// Formats a double the way error messages and reports print it.
std::string formatNumber(double value);

}  // namespace eqhb
