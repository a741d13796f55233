#include "eqhb/output/study_json.h"

#include <cmath>

#include "eqhb/checked_file.h"

namespace eqhb::output {

namespace {

nlohmann::json numberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json sampleJson(int id, const SampleResult& r, const StudySettings& settings) {
  nlohmann::json s;
  s["sample"] = id;
  for (std::size_t p = 0; p < r.parameters.size(); ++p) s["parameters"][settings.plan.parameters[p].path] = r.parameters[p];
  s["status"] = r.ok ? "ok" : "failed";
  if (!r.ok) s["reason"] = r.reason;
  s["start"] = r.start;
  s["peak_omega"] = r.ok ? numberOrNull(r.omega) : nullptr;
  s["first_harmonic"] = nlohmann::json::array();
  s["max_abs"] = nlohmann::json::array();
  for (double v : r.first_harmonic) s["first_harmonic"].push_back(numberOrNull(v));
  for (double v : r.max_abs) s["max_abs"].push_back(numberOrNull(v));
  if (settings.mode == StudyMode::kPeak) s["peaks"] = r.peaks;
  s["solves"] = r.solves;
  s["iterations"] = r.iterations;
  s["seconds"] = r.seconds;
  s["worker"] = r.worker;
  if (!r.curve.empty()) s["curve"] = r.curve;
  return s;
}

}  // namespace

nlohmann::json studyJson(const app::StudyRun& run) {
  const StudySettings& settings = run.setup.settings;
  nlohmann::json j;
  j["scene"] = run.setup.scene_name;
  j["mode"] = settings.mode == StudyMode::kPeak ? "peak" : "sweep";
  j["dof"] = settings.peak.dof + 1;
  // Names per DOF (the order of each sample's first_harmonic and max_abs),
  // the peak DOF's, and those of study.csv's columns.
  std::vector<std::string> labels = settings.dof_labels;
  for (int i = static_cast<int>(labels.size()); i < settings.dofs; ++i) labels.push_back("x" + std::to_string(i + 1));
  j["dof_labels"] = labels;
  j["dof_label"] = settings.peak.dof >= 0 && settings.peak.dof < settings.dofs ? labels[settings.peak.dof] : "";
  j["shown"] = nlohmann::json::array();
  for (int i : settings.csv_dofs)
    if (i >= 0 && i < settings.dofs) j["shown"].push_back(labels[i]);
  j["range"] = {settings.peak.from, settings.peak.to};
  j["parameters"] = nlohmann::json::array();
  for (const auto& p : settings.plan.parameters) j["parameters"].push_back(p.path);
  j["samples"] = nlohmann::json::array();
  for (const auto& [id, r] : run.rows) j["samples"].push_back(sampleJson(id, r, settings));
  return j;
}

void writeStudyJson(const std::string& path, const app::StudyRun& run) {
  writeFileChecked(path, studyJson(run).dump(1) + "\n");
}

}  // namespace eqhb::output
