#include "eqhb/studies/study_journal.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "eqhb/error.h"

namespace eqhb {

namespace {

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

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

bool toInt(const std::string& text, int* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  *value = static_cast<int>(v);
  return *end == '\0';
}

}  // namespace

std::string studyCsvHeader(const StudySettings& settings) {
  std::string h = "sample";
  for (const auto& p : settings.plan.parameters) h += "," + field(p.path);
  h += ",status,start,peak_omega";
  for (int i = 1; i <= settings.dofs; ++i) h += ",first_harmonic_x" + std::to_string(i);
  for (int i = 1; i <= settings.dofs; ++i) h += ",max_abs_x" + std::to_string(i);
  return h + ",peaks,solves,iterations,seconds,worker,curve,reason";
}

std::string studyCsvRow(const SampleResult& r, int dofs) {
  std::string row = std::to_string(r.id);
  for (double v : r.parameters) row += "," + number(v);
  row += r.ok ? ",ok," : ",failed,";
  row += field(r.start) + "," + number(r.ok ? r.omega : NAN);
  for (int i = 0; i < dofs; ++i)
    row += "," + number(r.ok && i < static_cast<int>(r.first_harmonic.size()) ? r.first_harmonic[i] : NAN);
  for (int i = 0; i < dofs; ++i)
    row += "," + number(r.ok && i < static_cast<int>(r.max_abs.size()) ? r.max_abs[i] : NAN);
  row += "," + std::to_string(r.peaks) + "," + std::to_string(r.solves) + "," + std::to_string(r.iterations) + "," + number(r.seconds) + "," +
         std::to_string(r.worker) + "," + field(r.curve) + "," + field(r.reason);
  return row;
}

bool parseStudyCsvRow(const std::string& line, int parameters, int dofs, SampleResult* r) {
  std::vector<std::string> f;
  if (!splitCsv(line, &f) || static_cast<int>(f.size()) != 1 + parameters + 3 + 2 * dofs + 7) return false;
  *r = SampleResult();
  std::size_t k = 0;
  if (!toInt(f[k++], &r->id) || r->id < 0) return false;
  r->parameters.resize(parameters);
  for (int p = 0; p < parameters; ++p)
    if (!toDouble(f[k++], &r->parameters[p])) return false;
  const std::string status = f[k++];
  if (status != "ok" && status != "failed") return false;
  r->ok = status == "ok";
  r->start = f[k++];
  if (!toDouble(f[k++], &r->omega)) return false;
  r->first_harmonic.resize(dofs);
  r->max_abs.resize(dofs);
  for (int i = 0; i < dofs; ++i)
    if (!toDouble(f[k++], &r->first_harmonic[i])) return false;
  for (int i = 0; i < dofs; ++i)
    if (!toDouble(f[k++], &r->max_abs[i])) return false;
  if (!toInt(f[k++], &r->peaks) || !toInt(f[k++], &r->solves) || !toInt(f[k++], &r->iterations) || !toDouble(f[k++], &r->seconds) ||
      !toInt(f[k++], &r->worker))
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
  for (const auto& o : s.overrides) out << "set = " << o << "\n";
  out << "mode = " << (s.mode == StudyMode::kPeak ? "peak" : "sweep") << "\n"
      << "range = " << number(s.peak.from) << " " << number(s.peak.to) << "\n"
      << "dof = " << s.peak.dof << "\n"
      << "system = " << (s.peak.condensed ? "condensed" : "full") << "\n";
  if (s.mode == StudyMode::kPeak)
    out << "coarse_points = " << s.peak.coarse_points << "\nmax_peaks = " << s.peak.max_peaks << "\n";
  if (s.mode == StudyMode::kSweep) out << "step = " << number(s.sweep_step) << "\n";
  out << "solver = " << solver_name << "\n"
      << "tolerance = " << number(s.solver_options.residual_tolerance) << "\n"
      << "max_iterations = " << s.solver_options.max_iterations << "\n"
      << "max_evaluations = " << s.solver_options.max_evaluations << "\n";
  for (const auto& [k, v] : s.solver_options.backend) out << "option = " << k << "=" << v << "\n";
  for (const auto& p : s.plan.parameters) out << "vary = " << p.path << "\n";
  out << "samples = " << s.plan.samples.size() << "\n";
  // The sample values themselves: a grid or a hypercube (and its seed) is
  // fully described by them.
  for (const auto& sample : s.plan.samples) {
    for (std::size_t p = 0; p < sample.size(); ++p) out << (p ? " " : "") << number(sample[p]);
    out << "\n";
  }
  return out.str();
}

StudyJournal::StudyJournal(const std::string& dir, const StudySettings& settings, const std::string& plan_text)
    : dir_(dir), settings_(settings) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(dir + (settings.mode == StudyMode::kSweep ? "/curves" : ""), error);
  if (error) throwInputError("--out", dir, "cannot create the folder (" + error.message() + ")");
  const std::string plan_path = dir + "/plan.txt";
  if (fs::exists(plan_path)) {
    std::ifstream in(plan_path);
    std::stringstream text;
    text << in.rdbuf();
    if (text.str() != plan_text)
      throwInputError("--out", dir,
                      "holds another study (its plan.txt differs from this command's): use another folder, or "
                      "delete that one to start over");
  } else {
    std::ofstream out(plan_path);
    out << plan_text;
    if (!out) throwInputError("--out", dir, "cannot write plan.txt");
  }
  const std::string journal_path = dir + "/journal.csv";
  const std::string header = studyCsvHeader(settings);
  const int parameters = static_cast<int>(settings.plan.parameters.size());
  bool needs_header = true;
  if (fs::exists(journal_path)) {
    std::ifstream in(journal_path);
    std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t start = 0, line_number = 0;
    while (start < content.size()) {
      const std::size_t end = content.find('\n', start);
      if (end == std::string::npos) break;  // cut short by a kill: recomputed
      const std::string line = content.substr(start, end - start);
      ++line_number;
      start = end + 1;
      if (line_number == 1) {
        if (line != header) throwInputError("--out", journal_path, "has an unexpected header");
        needs_header = false;
        continue;
      }
      SampleResult r;
      if (!parseStudyCsvRow(line, parameters, settings.dofs, &r) ||
          r.id >= static_cast<int>(settings.plan.samples.size()))
        throwInputError("--out", journal_path, "line " + std::to_string(line_number) + " is malformed");
      done_[r.id] = r;
    }
    // Drop a partial last row so that appends start on a fresh line.
    if (start < content.size()) fs::resize_file(journal_path, start, error);
    if (start == 0) needs_header = true;
  }
  journal_.open(journal_path, std::ios::app);
  if (!journal_) throwInputError("--out", journal_path, "cannot write the journal");
  if (needs_header) journal_ << header << "\n" << std::flush;
}

std::vector<int> StudyJournal::pending() const {
  std::vector<int> ids;
  for (int i = 0; i < static_cast<int>(settings_.plan.samples.size()); ++i)
    if (!done_.count(i)) ids.push_back(i);
  return ids;
}

void StudyJournal::append(const SampleResult& result) {
  const std::lock_guard<std::mutex> lock(mutex_);
  journal_ << studyCsvRow(result, settings_.dofs) << "\n" << std::flush;
  done_[result.id] = result;
}

void StudyJournal::appendRow(const std::string& row) {
  SampleResult r;
  if (!parseStudyCsvRow(row, static_cast<int>(settings_.plan.parameters.size()), settings_.dofs, &r))
    throw std::runtime_error("malformed result row received: " + row);
  append(r);
}

void StudyJournal::writeMerged() const {
  std::ofstream out(dir_ + "/study.csv");
  out << studyCsvHeader(settings_) << "\n";
  for (const auto& [id, r] : done_) out << studyCsvRow(r, settings_.dofs) << "\n";
  if (!out) throwInputError("--out", dir_ + "/study.csv", "cannot write the merged result");
}

}  // namespace eqhb
