// Numbers written to files that are read again (journals, CSV, overrides).
#pragma once

#include <string>

namespace eqhb {

// A double to 17 significant digits ("%.17g"): read back, the same double.
std::string formatRoundTrip(double value);

}  // namespace eqhb
