#include "eqhb/error.h"

#include <sstream>

namespace eqhb {

void throwInputError(const std::string& field, const std::string& value,
                     const std::string& rule) {
  throw InputError(field + " = " + value + ": " + rule);
}

std::string formatNumber(double value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}

}  // namespace eqhb
