#include "case_verdict.h"

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace eqhb::bench {

double agreementTolerance(double truncation_error) {
  // NaN (no truncation error known) compares false: the plain tolerance.
  return truncation_error * kTruncationFactor > kAgreementTolerance ? truncation_error * kTruncationFactor
                                                                    : kAgreementTolerance;
}

Verdict verdictOf(const Case& c) {
  if (!c.converged) return Verdict::kFailed;
  const bool has_reference = !std::isnan(c.error_reference), has_high = !std::isnan(c.error_high_h);
  if (!has_reference && !has_high) return Verdict::kUnchecked;
  const bool agrees = (has_reference && c.error_reference <= agreementTolerance(c.truncation_error)) ||
                      (has_high && c.error_high_h <= kAgreementTolerance);
  return agrees ? Verdict::kSolved : Verdict::kDisagrees;
}

const char* verdictName(Verdict verdict) {
  switch (verdict) {
    case Verdict::kSolved: return "solved";
    case Verdict::kDisagrees: return "disagrees";
    case Verdict::kUnchecked: return "unchecked";
    case Verdict::kFailed: return "failed";
  }
  return "failed";
}

std::string verdictRule() {
  std::ostringstream rule;
  rule << "a case is solved when the backend converged (‖g‖ within tolerance and the laws' physics checks passed) "
          "and its answer is within "
       << kAgreementTolerance
       << " relative L2 error of the displacements (worst DOF) of the scene's 4x-H solution or of its reference: "
          "a time-domain run, or for a Signorini wall the exact periodic orbit with elastic impacts (e = 1), the "
          "orbit its harmonic balance approaches as H grows; against that orbit the tolerance is max("
       << kAgreementTolerance << ", " << kTruncationFactor
       << " x the method's truncation error at the case's H), the truncation error being the reference harmonic "
          "balance at that H against the orbit (no solver comes nearer than the method; contact at H = 20: 0.103). "
          "A converged answer that agrees with none of these (a spurious root, another solution branch, or too "
          "few harmonics for the law) counts as a failure";
  return rule.str();
}

namespace {

using CaseKey = std::tuple<std::string, std::string, std::string, int>;  // scene, form, system, H

CaseKey keyOf(const Case& c) { return {c.scene, c.form, c.system, c.harmonics}; }

struct BackendScore {
  std::set<CaseKey> solved;
  int disagreements = 0;
  double log_time_sum = 0.0;
};

}  // namespace

DefaultChoice chooseDefault(const std::vector<Case>& cases) {
  std::map<std::string, BackendScore> scores;
  std::set<CaseKey> checked;
  for (const Case& c : cases) {
    if (c.study != "scenes") continue;
    const Verdict v = verdictOf(c);
    auto& score = scores[c.solver];
    if (v == Verdict::kSolved) {
      score.solved.insert(keyOf(c));
      score.log_time_sum += std::log(std::max(c.median_seconds, 1e-9));
    }
    if (v == Verdict::kDisagrees) ++score.disagreements;
    if (v == Verdict::kSolved || v == Verdict::kDisagrees) checked.insert(keyOf(c));
  }
  // Cases with a reference: those some backend's answer could be checked on,
  // plus failures on scenes that have references (a failure is checked too).
  for (const Case& c : cases)
    if (c.study == "scenes" && verdictOf(c) == Verdict::kFailed && checked.count(keyOf(c)) == 0) {
      bool scene_checked = false;
      for (const auto& k : checked) scene_checked = scene_checked || std::get<0>(k) == c.scene;
      if (scene_checked) checked.insert(keyOf(c));
    }
  DefaultChoice choice;
  choice.cases = static_cast<int>(checked.size());
  auto mean_log_time = [](const BackendScore& s) {
    return s.solved.empty() ? INFINITY : s.log_time_sum / s.solved.size();
  };
  const BackendScore* best = nullptr;
  for (const auto& [name, score] : scores) {
    if (best == nullptr || score.solved.size() > best->solved.size() ||
        (score.solved.size() == best->solved.size() && mean_log_time(score) < mean_log_time(*best))) {
      best = &score;
      choice.default_backend = name;
    }
  }
  if (best == nullptr) return choice;
  choice.default_solved = static_cast<int>(best->solved.size());
  choice.default_disagreements = best->disagreements;
  size_t most_rescued = 0;
  for (const auto& [name, score] : scores) {
    if (&score == best) continue;
    size_t rescued = 0;
    for (const auto& k : score.solved) rescued += best->solved.count(k) == 0;
    if (rescued > most_rescued) {
      most_rescued = rescued;
      choice.fallback_backend = name;
    }
  }
  choice.either_solved = choice.default_solved + static_cast<int>(most_rescued);
  return choice;
}

}  // namespace eqhb::bench
