// Checks made on a scene text before the TOML parser sees it. Debian's
// toml11 reads past its buffer on a literal string holding invalid UTF-8 and
// recurses once per nesting level of arrays and inline tables (a deep enough
// file overflows the stack), so the text is refused first when it is larger
// than kMaxSceneBytes, is not valid UTF-8, or nests arrays / inline tables
// deeper than kMaxTomlNesting.
#pragma once

#include <cstddef>
#include <string>

namespace eqhb {

inline constexpr std::size_t kMaxSceneBytes = 16u << 20;  // 16 MiB
inline constexpr int kMaxTomlNesting = 32;

// Throws InputError "SOURCE: line L: ..." naming what is wrong.
void checkTomlText(const std::string& text, const std::string& source);

}  // namespace eqhb
