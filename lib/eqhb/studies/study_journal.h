// What a study keeps on disk, so that it can stop anywhere and resume:
//   DIR/lock         held (flock) by the one study running in DIR
//   DIR/plan.txt     the study's definition; a resumed study must match it
//   DIR/journal.csv  the plan's fingerprint (first line), the CSV header,
//                    then one row per finished sample (ok or failed),
//                    written as each finishes, in completion order
//   DIR/study.csv    the merged result: every sample's row, in sample order,
//                    with the columns of the DOFs the study shows
// Rows are CSV with doubles printed to round-trip ("%.17g"); the free-text
// reason is the last column, quoted. A row cut short by a kill (no final
// newline) is ignored on reading; every other row is checked against the
// plan, so that a journal is never taken for another study's answers.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "eqhb/checked_file.h"
#include "eqhb/studies/study_folder_lock.h"
#include "eqhb/studies/study_sample.h"

namespace eqhb {

// The journal's header and rows have every DOF's columns; `dofs` picks
// some (0-based, in order) for study.csv. Columns are named by
// settings.dof_labels ("first_harmonic_w3"), else "x3".
std::string studyCsvHeader(const StudySettings& settings);
std::string studyCsvHeader(const StudySettings& settings, const std::vector<int>& dofs);
std::string studyCsvRow(const SampleResult& result, int dofs);
std::string studyCsvRow(const SampleResult& result, const std::vector<int>& dofs);
// Parses a row written by studyCsvRow; false if it is malformed, with the
// column and why in `why` when given. Integers must fit an int exactly.
bool parseStudyCsvRow(const std::string& line, int parameters, int dofs, SampleResult* result,
                      std::string* why = nullptr);

// Canonical text of the definition (the scene file's path and a hash of its
// bytes, overrides, samples, mode, range, solver options) compared on resume.
std::string studyPlanText(const StudySettings& settings, const std::string& solver_name);
// The study's identity: FNV-1a (64 bits) of its plan text, as 16 hex digits.
std::string studyFingerprint(const std::string& plan_text);

class StudyJournal {
 public:
  // Creates DIR (and DIR/curves for sweeps) and locks it; checks that
  // plan.txt, if there, is `plan_text` and that journal.csv, if there, is
  // this plan's (its fingerprint) and each of its rows one of this plan's
  // samples, with the sample's values; then writes plan.txt if missing.
  // Throws InputError naming the folder, or the file and line, and what
  // differs; IoError if a file cannot be written.
  StudyJournal(const std::string& dir, const StudySettings& settings, const std::string& plan_text);
  const std::map<int, SampleResult>& done() const { return done_; }
  // Sample ids not yet in the journal, in study order.
  std::vector<int> pending() const;
  // Writes one row (thread-safe). Throws IoError if the write fails, and
  // from then on for every row (rows after a cut one would be unreadable).
  // An ok result with a non-finite value is written as a failed sample. A
  // sample already in the journal (computed again to rebuild a warm start,
  // see samplesToCompute) is not written again.
  void append(const SampleResult& result);
  // Appends a row already formatted by studyCsvRow (from another rank).
  void appendRow(const std::string& row);
  // Syncs the journal and writes DIR/study.csv from every row, in sample
  // order (IoError if either fails).
  void writeMerged();

 private:
  void readJournal(const std::string& path, const std::string& fingerprint, bool plan_was_there);
  void checkRow(const SampleResult& row, const std::string& where, const std::map<int, int>& lines) const;

  std::string dir_;
  const StudySettings& settings_;
  StudyFolderLock lock_;
  std::map<int, SampleResult> done_;
  std::unique_ptr<AppendOnlyFile> journal_;
  std::string failure_;  // of a failed write: the journal takes no more rows
  std::mutex mutex_;
};

}  // namespace eqhb
