// The benchmark's other sections: failure maps, compliant contact, frequency
// response curves, the MGH comparison and the scale study's settings. Each
// runs its study, writes its data file into the output folder and returns
// what the report shows of it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench_options.h"
#include "failure_maps.h"

namespace eqhb::bench {

// 3. Failure maps of the mapped scenes (quick: friction-1d alone) for the
// built backends among the mapped ones.
std::vector<FailureRow> runFailureStudy(const BenchOptions& options,
                                        const std::vector<std::filesystem::path>& scenes,
                                        const std::vector<std::string>& built);
void writeFailureCsv(const std::string& path, const std::vector<FailureRow>& rows);
// Per backend: converged, cases, success rate.
std::string successTable(const std::vector<FailureRow>& rows);

// Compliant normal contact against the exact Signorini law, k_n = 1 .. 1e6
// (compliant.csv); returns the report's table.
std::string runCompliantStudy(const BenchOptions& options);

// 4. Frequency-response curves of every scene with a [sweep], sequential and
// arclength (curve_SCENE_*.csv); returns the report's table rows.
std::string runCurves(const BenchOptions& options, const std::vector<std::filesystem::path>& scenes);

// The own dogleg against MINPACK's hybrj on the Moré–Garbow–Hillstrom problems.
std::string mghTable(const std::vector<std::string>& built);

// The scale study's backends and its introduction in the report.
std::vector<std::string> scaleBackends(bool quick);
std::string scaleIntroduction();

}  // namespace eqhb::bench
