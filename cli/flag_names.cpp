#include "flag_names.h"

#include <cctype>
#include <utility>

namespace eqhb::cli {

namespace {
// Fields whose flag differs from the field; fields such as max_iterations,
// which the library has always named so, keep their name.
const std::pair<const char*, const char*> kFlags[] = {
    {"from_harmonics", "--from-harmonics"}, {"max_harmonics", "--max-harmonics"},
    {"refine_harmonics", "--refine-harmonics"}, {"cold_start", "--cold-start"},
    {"linear_algebra", "--linear-algebra"}, 
    {"accuracy", "--accuracy"}, {"fallback", "--fallback"},
    {"options", "--option"}, {"repeat", "--repeat"},
    {"form", "--form"}, {"rho", "--rho"},
    {"from_hb", "--from-hb"},
    // Phrases, replaced wherever they occur.
    {"refine = shoot", "--refine shoot"},
};

bool wordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; }
}  // namespace

std::string withFlagNames(const std::string& message) {
  std::string out = message;
  for (const auto& [field, flag] : kFlags) {
    const std::string name = field;
    if (name.find(' ') != std::string::npos) {
      for (size_t at = out.find(name); at != std::string::npos; at = out.find(name, at + 1))
        out.replace(at, name.size(), flag);
      continue;
    }
    if (out.rfind(name + " = ", 0) == 0 || out.rfind(name + ": ", 0) == 0) out = flag + out.substr(name.size());
    if (name.find('_') == std::string::npos) continue;
    for (size_t at = out.find(name); at != std::string::npos; at = out.find(name, at + 1)) {
      const bool starts = at == 0 || !wordChar(out[at - 1]);
      const bool ends = at + name.size() == out.size() || !wordChar(out[at + name.size()]);
      if (starts && ends) out.replace(at, name.size(), flag);
    }
  }
  return out;
}

}  // namespace eqhb::cli
