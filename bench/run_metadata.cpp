#include "run_metadata.h"

#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "build_info.h"
#include "eqhb/version.h"
#include "terminal/run_program.h"

namespace eqhb::bench {

namespace {

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// The first "model name" of /proc/cpuinfo.
std::string cpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return trimmed(line.substr(colon + 2));
    }
  return "unknown";
}

// "name=version;name=version" (from CMake) as an object.
nlohmann::json libraryVersions() {
  nlohmann::json out = nlohmann::json::object();
  std::istringstream list(EQHB_LIBRARY_VERSIONS);
  for (std::string item; std::getline(list, item, ';');) {
    const auto eq = item.find('=');
    if (eq != std::string::npos) out[item.substr(0, eq)] = item.substr(eq + 1);
  }
  return out;
}

}  // namespace

nlohmann::json runMetadata() {
  const std::string source = EQHB_SOURCE_DIR;
  const auto commit = cli::programOutput({"git", "-C", source, "rev-parse", "HEAD"});
  const auto status = cli::programOutput({"git", "-C", source, "status", "--porcelain", "--untracked-files=no"});
  char date[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return {{"eqhb_version", EQHB_VERSION},
          {"commit", commit ? trimmed(*commit) : "unknown"},
          {"uncommitted_changes", status ? !trimmed(*status).empty() : false},
          {"date", date},
          {"cpu", cpuModel()},
          {"hardware_threads", std::thread::hardware_concurrency()},
          {"compiler", EQHB_CXX_COMPILER},
          {"build_type", EQHB_BUILD_TYPE},
          {"cxx_flags", EQHB_CXX_FLAGS},
          {"libraries", libraryVersions()}};
}

}  // namespace eqhb::bench
