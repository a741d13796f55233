// A check for numeric options: CLI11 converts through long double, so
// "--omega 1e-400" would arrive as 0 and "1e400" as infinity, and the
// message would then speak of a value the user never typed. The check reads
// the text as a double first and refuses what does not fit.
#pragma once

#include <CLI/CLI.hpp>

namespace eqhb::cli {

// "VALUE underflows to 0; not representable ..." for a nonzero literal that
// rounds to 0, "VALUE overflows; ..." for one beyond the largest double;
// anything else is left to the option's own conversion.
const CLI::Validator& representableNumber();

}  // namespace eqhb::cli
