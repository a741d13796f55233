#include "eqhb/round_trip.h"

#include <cstdio>

namespace eqhb {

std::string formatRoundTrip(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace eqhb
