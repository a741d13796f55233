#include "eqhb/studies/study_journal.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "eqhb/error.h"
#include "eqhb/round_trip.h"
#include "eqhb/io_error.h"

namespace eqhb {

namespace {

// Quoted when it holds a comma, quote or line break; quotes doubled.
std::string field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return quoted + "\"";
}

bool splitCsv(const std::string& line, std::vector<std::string>* fields) {
  fields->clear();
  std::string current;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        current += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        current += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields->push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (quoted) return false;
  fields->push_back(current);
  return true;
}

bool toDouble(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return *end == '\0';
}

// An int written in full: no truncation of a larger number.
bool toInt(const std::string& text, int* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE || v < INT_MIN || v > INT_MAX) return false;
  *value = static_cast<int>(v);
  return true;
}

std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (unsigned char c : bytes) hash = (hash ^ c) * 0x100000001b3ull;
  return hash;
}

std::string hex64(std::uint64_t value) {
  char text[20];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throwIoError(path, "cannot read");
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throwIoError(path, "cannot read");
  return content;
}

// The first line where two texts differ, for a message: "line N is 'A'
// there, 'B' here".
std::string firstDifference(const std::string& there, const std::string& here) {
  std::istringstream a(there), b(here);
  std::string x, y;
  for (int line = 1;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(a, x)), more_b = static_cast<bool>(std::getline(b, y));
    if (!more_a && !more_b) return "they differ only in line ends";
    if (!more_a) x = "(end)";
    if (!more_b) y = "(end)";
    if (x != y || !more_a || !more_b)
      return "line " + std::to_string(line) + " is '" + x + "' there, '" + y + "' for this command";
  }
}

// First line of a journal: the plan it belongs to.
const char* const kJournalIdentity = "# eqhb study journal, plan fingerprint ";

}  // namespace

namespace {
std::vector<int> everyDof(int dofs) {
  std::vector<int> all(std::max(dofs, 0));
  for (int i = 0; i < dofs; ++i) all[i] = i;
  return all;
}
}  // namespace

std::string studyCsvHeader(const StudySettings& settings) { return studyCsvHeader(settings, everyDof(settings.dofs)); }

std::string studyCsvHeader(const StudySettings& settings, const std::vector<int>& dofs) {
  auto label = [&](int i) {
    return static_cast<size_t>(i) < settings.dof_labels.size() ? settings.dof_labels[i] : "x" + std::to_string(i + 1);
  };
  std::string h = "sample";
  for (const auto& p : settings.plan.parameters) h += "," + field(p.path);
  h += ",status,start,peak_omega";
  for (int i : dofs) h += ",first_harmonic_" + label(i);
  for (int i : dofs) h += ",max_abs_" + label(i);
  return h + ",peaks,solves,iterations,seconds,worker,curve,reason";
}

std::string studyCsvRow(const SampleResult& r, int dofs) { return studyCsvRow(r, everyDof(dofs)); }

std::string studyCsvRow(const SampleResult& r, const std::vector<int>& dofs) {
  std::string row = std::to_string(r.id);
  for (double v : r.parameters) row += "," + formatRoundTrip(v);
  row += r.ok ? ",ok," : ",failed,";
  row += field(r.start) + "," + formatRoundTrip(r.ok ? r.omega : NAN);
  for (int i : dofs)
    row += "," + formatRoundTrip(r.ok && i < static_cast<int>(r.first_harmonic.size()) ? r.first_harmonic[i] : NAN);
  for (int i : dofs)
    row += "," + formatRoundTrip(r.ok && i < static_cast<int>(r.max_abs.size()) ? r.max_abs[i] : NAN);
  row += "," + std::to_string(r.peaks) + "," + std::to_string(r.solves) + "," + std::to_string(r.iterations) + "," + formatRoundTrip(r.seconds) + "," +
         std::to_string(r.worker) + "," + field(r.curve) + "," + field(r.reason);
  return row;
}

bool parseStudyCsvRow(const std::string& line, int parameters, int dofs, SampleResult* r, std::string* why) {
  std::string ignored;
  std::string& reason = why ? *why : ignored;
  std::vector<std::string> f;
  const int columns = 1 + parameters + 3 + 2 * dofs + 7;
  if (!splitCsv(line, &f)) return reason = "an unclosed quote", false;
  if (static_cast<int>(f.size()) != columns)
    return reason = std::to_string(f.size()) + " columns, the header has " + std::to_string(columns), false;
  *r = SampleResult();
  std::size_t k = 0;
  auto bad = [&](const std::string& column, const std::string& rule) {
    reason = column + " = '" + f[k - 1] + "': " + rule;
    return false;
  };
  auto integer = [&](const char* column, int* value) {
    return toInt(f[k++], value) && *value >= 0 ? true : bad(column, "must be an integer in [0, 2147483647]");
  };
  auto real = [&](const std::string& column, double* value) {
    return toDouble(f[k++], value) ? true : bad(column, "must be a number");
  };
  if (!integer("sample", &r->id)) return false;
  r->parameters.resize(parameters);
  for (int p = 0; p < parameters; ++p)
    if (!real("parameter " + std::to_string(p + 1), &r->parameters[p])) return false;
  const std::string status = f[k++];
  if (status != "ok" && status != "failed") return bad("status", "must be ok or failed");
  r->ok = status == "ok";
  r->start = f[k++];
  if (!real("peak_omega", &r->omega)) return false;
  r->first_harmonic.resize(dofs);
  r->max_abs.resize(dofs);
  for (int i = 0; i < dofs; ++i)
    if (!real("first_harmonic_x" + std::to_string(i + 1), &r->first_harmonic[i])) return false;
  for (int i = 0; i < dofs; ++i)
    if (!real("max_abs_x" + std::to_string(i + 1), &r->max_abs[i])) return false;
  if (!integer("peaks", &r->peaks) || !integer("solves", &r->solves) || !integer("iterations", &r->iterations) ||
      !real("seconds", &r->seconds) || !integer("worker", &r->worker))
    return false;
  r->curve = f[k++];
  r->reason = f[k++];
  if (!r->ok) {
    r->first_harmonic.clear();
    r->max_abs.clear();
  }
  return true;
}

std::string studyPlanText(const StudySettings& s, const std::string& solver_name) {
  std::ostringstream out;
  out << "scene = " << std::filesystem::absolute(s.scene_path).lexically_normal().string() << "\n";
  // The scene's content too: an edited scene is another study. (Files the
  // scene names, such as Matrix Market matrices, are not read here.)
  out << "scene_fnv1a64 = " << hex64(fnv1a(readFile(s.scene_path))) << "\n";
  for (const auto& o : s.overrides) out << "set = " << o << "\n";
  out << "mode = " << (s.mode == StudyMode::kPeak ? "peak" : "sweep") << "\n"
      << "range = " << formatRoundTrip(s.peak.from) << " " << formatRoundTrip(s.peak.to) << "\n"
      << "dof = " << s.peak.dof + 1 << "\n"
      << "system = " << (s.peak.condensed ? "condensed" : "full") << "\n";
  if (s.mode == StudyMode::kPeak)
    out << "coarse_points = " << s.peak.coarse_points << "\nmax_peaks = " << s.peak.max_peaks << "\n";
  if (s.mode == StudyMode::kSweep) out << "step = " << formatRoundTrip(s.sweep_step) << "\n";
  out << "solver = " << solver_name << "\n"
      << "tolerance = " << formatRoundTrip(s.solver_options.residual_tolerance) << "\n"
      << "max_iterations = " << s.solver_options.max_iterations << "\n"
      << "max_evaluations = " << s.solver_options.max_evaluations << "\n";
  for (const auto& [k, v] : s.solver_options.backend) out << "option = " << k << "=" << v << "\n";
  for (const auto& p : s.plan.parameters) out << "vary = " << p.path << "\n";
  out << "samples = " << s.plan.samples.size() << "\n";
  // The sample values themselves: a grid or a hypercube (and its seed) is
  // fully described by them.
  for (const auto& sample : s.plan.samples) {
    for (std::size_t p = 0; p < sample.size(); ++p) out << (p ? " " : "") << formatRoundTrip(sample[p]);
    out << "\n";
  }
  return out.str();
}

std::string studyFingerprint(const std::string& plan_text) { return hex64(fnv1a(plan_text)); }

namespace {

// Creates the folder (before anything else, so that it can be locked).
const std::string& createdFolder(const std::string& dir, const StudySettings& settings) {
  std::error_code error;
  std::filesystem::create_directories(dir + (settings.mode == StudyMode::kSweep ? "/curves" : ""), error);
  if (error) throwInputError("out", dir, "cannot create the folder (" + error.message() + ")");
  return dir;
}

bool finite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

StudyJournal::StudyJournal(const std::string& dir, const StudySettings& settings, const std::string& plan_text)
    : dir_(createdFolder(dir, settings)), settings_(settings), lock_(dir_) {
  namespace fs = std::filesystem;
  const std::string plan_path = dir + "/plan.txt";
  const bool plan_was_there = fs::exists(plan_path);
  if (plan_was_there) {
    const std::string there = readFile(plan_path);
    if (there != plan_text)
      throwInputError("out", dir,
                      "holds another study (its plan.txt differs from this command's: " +
                          firstDifference(there, plan_text) +
                          "): use another folder, or delete that one to start over");
  }
  readJournal(dir + "/journal.csv", studyFingerprint(plan_text), plan_was_there);
  if (!plan_was_there) writeFileChecked(plan_path, plan_text);
}

void StudyJournal::readJournal(const std::string& path, const std::string& fingerprint, bool plan_was_there) {
  namespace fs = std::filesystem;
  const std::string identity = kJournalIdentity + fingerprint;
  const std::string header = studyCsvHeader(settings_);
  const int parameters = static_cast<int>(settings_.plan.parameters.size());
  std::size_t start = 0;
  if (fs::exists(path)) {
    const std::string content = readFile(path);
    std::map<int, int> lines;  // sample id -> its line
    std::size_t line_number = 0;
    while (start < content.size()) {
      const std::size_t end = content.find('\n', start);
      if (end == std::string::npos) break;  // cut short by a kill: recomputed
      const std::string line = content.substr(start, end - start);
      const std::string where = path + ":" + std::to_string(++line_number);
      start = end + 1;
      if (line_number == 1) {
        if (line.rfind(kJournalIdentity, 0) != 0)
          throwInputError(where, line.substr(0, 60),
                          "is not the first line of an eqhb study journal ('" + std::string(kJournalIdentity) +
                              "…'): use another folder, or delete that one to start over");
        if (line != identity)
          throwInputError("out", dir_,
                          "holds another study: journal.csv has plan fingerprint " +
                              line.substr(std::string(kJournalIdentity).size()) + ", this command's is " +
                              fingerprint +
                              (plan_was_there ? "" : " (plan.txt, which would say what differs, is missing)") +
                              ": use another folder, or delete that one to start over");
        continue;
      }
      if (line_number == 2) {
        if (line != header) throwInputError(where, line.substr(0, 60), "is not this study's CSV header");
        continue;
      }
      SampleResult r;
      std::string why;
      if (!parseStudyCsvRow(line, parameters, settings_.dofs, &r, &why)) throw InputError(where + " " + why);
      checkRow(r, where, lines);
      lines[r.id] = static_cast<int>(line_number);
      done_[r.id] = r;
    }
    if (line_number < 2) start = 0;  // no whole header yet: both lines written anew
    // Drop a partial last row so that appends start on a fresh line.
    if (start < content.size()) {
      std::error_code error;
      fs::resize_file(path, start, error);
      if (error) {
        errno = error.value();
        throwIoError(path, "cannot cut the partial last row");
      }
    }
  }
  journal_ = std::make_unique<AppendOnlyFile>(path);
  if (start == 0) journal_->append(identity + "\n" + header + "\n");
}

// A row of this plan: a sample id in range, seen once, with that sample's
// values; an ok row with finite results; its curve file, if it names one.
void StudyJournal::checkRow(const SampleResult& r, const std::string& where, const std::map<int, int>& lines) const {
  const int samples = static_cast<int>(settings_.plan.samples.size());
  if (r.id >= samples)
    throwInputError(where + " sample", std::to_string(r.id),
                    "this study has samples 0 to " + std::to_string(samples - 1));
  if (lines.count(r.id))
    throwInputError(where + " sample", std::to_string(r.id), "is already on line " + std::to_string(lines.at(r.id)));
  for (std::size_t p = 0; p < r.parameters.size(); ++p)
    if (r.parameters[p] != settings_.plan.samples[r.id][p])
      throwInputError(where + " " + settings_.plan.parameters[p].path, formatRoundTrip(r.parameters[p]),
                      "sample " + std::to_string(r.id) + " of this study has " + formatRoundTrip(settings_.plan.samples[r.id][p]));
  if (r.ok && !(std::isfinite(r.omega) && finite(r.first_harmonic) && finite(r.max_abs)))
    throwInputError(where + " sample", std::to_string(r.id),
                    "is ok but has a non-finite peak_omega, first_harmonic or max_abs");
  if (!r.curve.empty()) {
    char expected[64];
    std::snprintf(expected, sizeof expected, "curves/sample_%06d.csv", r.id);
    if (settings_.mode != StudyMode::kSweep || r.curve != expected)
      throwInputError(where + " curve", r.curve,
                      settings_.mode == StudyMode::kSweep ? "must be " + std::string(expected)
                                                          : "must be empty (a --peak study writes no curves)");
    if (!std::filesystem::exists(dir_ + "/" + r.curve))
      throwInputError(where + " curve", r.curve, "is missing from the study folder");
  }
}

std::vector<int> StudyJournal::pending() const {
  std::vector<int> ids;
  for (int i = 0; i < static_cast<int>(settings_.plan.samples.size()); ++i)
    if (!done_.count(i)) ids.push_back(i);
  return ids;
}

void StudyJournal::append(const SampleResult& result) {
  SampleResult r = result;
  if (r.ok && !(std::isfinite(r.omega) && finite(r.first_harmonic) && finite(r.max_abs))) {
    r.ok = false;
    r.reason = "the result is not finite (peak_omega " + formatRoundTrip(r.omega) + ")";
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  if (done_.count(r.id)) return;
  // Every later row fails as the first did (whichever thread reports first).
  if (!failure_.empty()) throw IoError(failure_);
  try {
    journal_->append(studyCsvRow(r, settings_.dofs) + "\n");
  } catch (const IoError& e) {
    failure_ = e.what();
    throw;
  }
  done_[r.id] = r;
}

void StudyJournal::appendRow(const std::string& row) {
  SampleResult r;
  std::string why;
  if (!parseStudyCsvRow(row, static_cast<int>(settings_.plan.parameters.size()), settings_.dofs, &r, &why))
    throw std::runtime_error("malformed result row received (" + why + "): " + row);
  append(r);
}

void StudyJournal::writeMerged() {
  journal_->sync();
  const std::vector<int> dofs = settings_.csv_dofs.empty() ? everyDof(settings_.dofs) : settings_.csv_dofs;
  std::string text = studyCsvHeader(settings_, dofs) + "\n";
  for (const auto& [id, r] : done_) text += studyCsvRow(r, dofs) + "\n";
  writeFileChecked(dir_ + "/study.csv", text);
}

}  // namespace eqhb
