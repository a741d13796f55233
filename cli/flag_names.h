// The library names an option by its field in the options structs
// ("from_harmonics = 9: ..."); the command line names its flag
// ("--from-harmonics = 9: ..."). This is the one table between the two.
#pragma once

#include <string>

namespace eqhb::cli {

// `message` with each option field named by its flag: a field at the start
// ("field = " or "field: "), a field with an underscore anywhere, and the
// phrases that set an option ("refine = shoot" is "--refine shoot").
std::string withFlagNames(const std::string& message);

}  // namespace eqhb::cli
