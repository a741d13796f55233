// The number a TOML value holds, refused when its literal is out of range.
// toml11 reads a float with an istream, which turns a literal below the
// smallest double (1e-400) into 0 and one above the largest (1e400) into
// the largest double, both without a word: a friction limit written 1e-400
// would quietly become no friction at all. The literal is read again here,
// from the source line toml11 keeps with every value.
#pragma once

#include <string>
#include <toml.hpp>

namespace eqhb {

// The literal of `value` as written ("1e-400"), or "" when unknown.
std::string tomlLiteral(const toml::value& value);

// For a floating value: "" when its literal is a representable double,
// otherwise the rule it breaks ("underflows to 0; not representable ...").
// Integers and other values: "".
std::string floatRangeProblem(const toml::value& value);

}  // namespace eqhb
