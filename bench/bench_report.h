// The benchmark's results: bench.json and bench.csv (every case), the
// backend advice per scene, and report.md.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cases.h"
#include "bench_options.h"
#include "scale_study.h"

namespace eqhb::bench {

// Writes bench.json (with the run's metadata) and bench.csv; returns the
// metadata.
nlohmann::json writeCaseData(const std::string& out, const std::vector<Case>& cases);

// Which backend to pick, per scene, from the scene study: a bullet list and
// the summary table's rows.
struct Advice {
  std::string bullets, summary_rows;
};
Advice adviseBackends(const std::vector<Case>& cases);

// What report.md is made of besides the cases.
struct ReportParts {
  nlohmann::json metadata;
  Advice advice;
  std::string truth_table, success_table, compliant_table, curve_rows, mgh_table, structure_names;
  std::vector<ScaleRow> scale;
};
void writeReport(const BenchOptions& options, const std::vector<Case>& cases, const ReportParts& parts);
// scenes.md: the summary, the advice and the scene table alone (--scenes-only).
void writeScenesReport(const BenchOptions& options, const std::vector<Case>& cases, const ReportParts& parts);

}  // namespace eqhb::bench
