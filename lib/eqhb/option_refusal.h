// The refusal of an options struct's isValid: one message shape,
// "FIELD = VALUE: RULE", for every library options check.
#pragma once

#include <string>

namespace eqhb {

// Sets *why (when given) to "FIELD = VALUE: RULE" and returns false.
inline bool refuseOption(std::string* why, const std::string& field, const std::string& value,
                         const std::string& rule) {
  if (why) *why = field + " = " + value + ": " + rule;
  return false;
}

}  // namespace eqhb
