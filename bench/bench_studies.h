// The benchmark's case studies: the backends on friction-1d, and every
// scene x formulation x system x backend (with variants of ρ and H).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench_cases.h"
#include "bench_options.h"
#include "bench_truth.h"

namespace eqhb::bench {

// The scenes of the problems folder, sorted: the small ones of the scene
// tables, and the structures with many DOFs measured in the scale study.
struct SceneLists {
  std::vector<std::filesystem::path> small, structures;
};
SceneLists listScenes(const std::string& problems);

// Names of the backends built in.
std::vector<std::string> builtBackends();

// 1. Backends on friction-1d (exact min/max form), H = 10 and 40.
std::vector<Case> runBackendStudy(const BenchOptions& options, const std::vector<std::string>& built);

// 2. Every scene x form x system x backend at the scene's harmonics, and
// (without quick) the variants; appends to `cases` and `truths`.
void runSceneStudy(const BenchOptions& options, const std::vector<std::filesystem::path>& scenes,
                   const std::vector<std::string>& built, std::vector<Case>& cases, std::vector<TruthStatus>& truths);

}  // namespace eqhb::bench
