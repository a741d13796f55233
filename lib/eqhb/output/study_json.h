// A parameter study's rows as one JSON object (the study folder's
// study.json, Python's eqhb.study): the scene, mode, DOF (number "dof" and
// name "dof_label"), every DOF's name ("dof_labels"), the names of study.csv's
// DOFs ("shown"), range and varied paths, and per sample its values, status, start, peak ω, first-harmonic
// amplitude and max|x| per DOF (null where not finite), counts, time,
// worker and, for sweeps, its curve file.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "eqhb/app/study.h"

namespace eqhb::output {

nlohmann::json studyJson(const app::StudyRun& run);
// Throws IoError naming the file that cannot be written.
void writeStudyJson(const std::string& path, const app::StudyRun& run);

}  // namespace eqhb::output
