#include "eqhb/scenes/toml_guard.h"

#include "eqhb/error.h"

namespace eqhb {

namespace {

// Length of the well-formed UTF-8 sequence at text[i] (RFC 3629: no overlong
// forms, no surrogates, nothing above U+10FFFF), or 0 if it is malformed.
std::size_t utf8Length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) -> unsigned {
    return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0x100u;
  };
  const auto continuation = [&](std::size_t k, unsigned lo = 0x80, unsigned hi = 0xBF) {
    const unsigned b = byte(k);
    return b >= lo && b <= hi;
  };
  const unsigned b0 = byte(0);
  if (b0 < 0x80) return 1;
  if (b0 >= 0xC2 && b0 <= 0xDF) return continuation(1) ? 2 : 0;
  if (b0 == 0xE0) return continuation(1, 0xA0) && continuation(2) ? 3 : 0;
  if (b0 == 0xED) return continuation(1, 0x80, 0x9F) && continuation(2) ? 3 : 0;
  if (b0 >= 0xE1 && b0 <= 0xEF) return continuation(1) && continuation(2) ? 3 : 0;
  if (b0 == 0xF0) return continuation(1, 0x90) && continuation(2) && continuation(3) ? 4 : 0;
  if (b0 >= 0xF1 && b0 <= 0xF3) return continuation(1) && continuation(2) && continuation(3) ? 4 : 0;
  if (b0 == 0xF4) return continuation(1, 0x80, 0x8F) && continuation(2) && continuation(3) ? 4 : 0;
  return 0;
}

bool startsWith(const std::string& text, std::size_t i, const char* token) {
  return text.compare(i, std::char_traits<char>::length(token), token) == 0;
}

}  // namespace

void checkTomlText(const std::string& text, const std::string& source) {
  if (text.size() > kMaxSceneBytes)
    throw InputError(source + ": " + std::to_string(text.size()) + " bytes: a scene file is at most " +
                     std::to_string(kMaxSceneBytes) + " bytes");
  int line = 1;
  const auto fail = [&](const std::string& what) {
    throw InputError(source + ": line " + std::to_string(line) + ": " + what);
  };
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8Length(text, i);
    if (n == 0) fail("not valid UTF-8 (byte " + std::to_string(i) + ")");
    if (text[i] == '\n') ++line;
    i += n;
  }
  // Depth of [ and { outside strings and comments. Table headers ([a],
  // [[a]]) count too, which only adds 2 at most.
  line = 1;
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
    } else if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
    } else if (startsWith(text, i, "\"\"\"") || startsWith(text, i, "'''")) {
      const std::string close = text.substr(i, 3);
      const bool basic = c == '"';
      for (i += 3; i < text.size() && !startsWith(text, i, close.c_str()); ++i) {
        if (basic && text[i] == '\\' && i + 1 < text.size()) ++i;  // an escaped character
        if (text[i] == '\n') ++line;
      }
      i += 2;
    } else if (c == '"' || c == '\'') {
      for (++i; i < text.size() && text[i] != c && text[i] != '\n'; ++i)
        if (c == '"' && text[i] == '\\' && i + 1 < text.size() && text[i + 1] != '\n') ++i;
      if (i < text.size() && text[i] == '\n') ++line;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxTomlNesting)
        fail("arrays or inline tables nested deeper than " + std::to_string(kMaxTomlNesting) + " levels");
    } else if (c == ']' || c == '}') {
      if (depth > 0) --depth;
    }
  }
}

}  // namespace eqhb
