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
    {"linear_algebra", "--linear-algebra"}, {"backbone_time_limit", "--backbone-time-limit"},
    {"accuracy_test", "--accuracy-test"}, {"accuracy", "--accuracy"}, {"fallback", "--fallback"},
    {"options", "--option"}, {"repeat", "--repeat"},
    {"form", "--form"}, {"formulation", "--formulation"}, {"rho", "--rho"},
    {"from_hb", "--from-hb"},
    {"from", "--from"}, {"to", "--to"}, {"step", "--step"},
    {"min_step", "--min-step"}, {"max_step", "--max-step"}, {"stability", "--stability"}, {"stability_method", "--stability-method"},
    {"stability_time_limit", "--stability-time-limit"}, {"curve_time_limit", "--curve-time-limit"},
    {"dof", "--dof"}, {"coarse_points", "--coarse-points"}, {"max_peaks", "--max-peaks"},
    {"show", "--show"}, {"peak_dof", "--peak-dof"}, {"vary", "--vary"}, {"lhs", "--lhs"}, {"out", "--out"}, {"threads", "--threads"},
    // Phrases, replaced wherever they begin a word.
    {"refine = shoot", "--refine shoot"},
    {"give from and to", "give --from and --to"}, {"differ from from", "differ from --from"},
    {"not with accuracy", "not with --accuracy"}, {"and > from", "and > --from"},
    {"vary ", "--vary "}, {"try system = full", "try --full"}, {"another solver", "another --solver"},
    {"more samples", "more --samples"}, {"larger max_points", "larger --max-points"},
};

bool wordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; }
}  // namespace

std::string withFlagNames(const std::string& message) {
  std::string out = message;
  for (const auto& [field, flag] : kFlags) {
    const std::string name = field;
    if (name.find(' ') != std::string::npos) {
      for (size_t at = out.find(name); at != std::string::npos;) {
        const bool starts = at == 0 || !wordChar(out[at - 1]);
        if (starts) out.replace(at, name.size(), flag);
        at = out.find(name, at + (starts ? std::string(flag).size() : 1));
      }
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
