// What a study keeps on disk, so that it can stop anywhere and resume:
//   DIR/plan.txt     the study's definition; a resumed study must match it
//   DIR/journal.csv  one row per finished sample (ok or failed), appended and
//                    flushed as each finishes, in completion order
//   DIR/study.csv    the merged result: every sample's row, in sample order
// Rows are CSV with doubles printed to round-trip ("%.17g"); the free-text
// reason is the last column, quoted. A row cut short by a kill (no final
// newline) is ignored on reading.
#pragma once

#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "eqhb/studies/study_sample.h"

namespace eqhb {

std::string studyCsvHeader(const StudySettings& settings);
std::string studyCsvRow(const SampleResult& result, int dofs);
// Parses a row written by studyCsvRow; false if it is malformed.
bool parseStudyCsvRow(const std::string& line, int parameters, int dofs, SampleResult* result);

// Canonical text of the definition (scene, overrides, samples, mode, range,
// solver options) compared on resume.
std::string studyPlanText(const StudySettings& settings, const std::string& solver_name);

class StudyJournal {
 public:
  // Creates DIR (and DIR/curves for sweeps), writes plan.txt or checks that
  // the one there is `plan_text` (InputError otherwise), and reads the rows
  // already in journal.csv.
  StudyJournal(const std::string& dir, const StudySettings& settings, const std::string& plan_text);
  const std::map<int, SampleResult>& done() const { return done_; }
  // Sample ids not yet in the journal, in study order.
  std::vector<int> pending() const;
  // Appends and flushes one row (thread-safe).
  void append(const SampleResult& result);
  // Appends a row already formatted by studyCsvRow (from another rank).
  void appendRow(const std::string& row);
  // Writes DIR/study.csv from every row, in sample order.
  void writeMerged() const;

 private:
  std::string dir_;
  const StudySettings& settings_;
  std::map<int, SampleResult> done_;
  std::ofstream journal_;
  std::mutex mutex_;
};

}  // namespace eqhb
