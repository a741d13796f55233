// Where and with what a benchmark ran, so that runs from two machines or two
// commits can be compared: commit, date, CPU, compiler, build type and the
// versions of the libraries eqhb was built against.
#pragma once

#include <nlohmann/json.hpp>

namespace eqhb::bench {

nlohmann::json runMetadata();

}  // namespace eqhb::bench
