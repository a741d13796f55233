#include "refine_options.h"

namespace eqhb::cli {

void addRefineOptions(CLI::App* cmd, RefineArguments& a) {
  cmd->add_option("--refine", a.method,
                  "shoot: harmonic balance followed by shooting; reports the exact periodic orbit (its Fourier "
                  "truncation on the same harmonics, its exact max|x|)")
      ->check(CLI::IsMember({"shoot"}));
  cmd->add_option("--restitution", a.restitution, "With --refine shoot: Newton impact coefficient e of contact laws")
      ->capture_default_str();
  cmd->add_option("--refine-harmonics", a.harmonics,
                  "With --refine shoot: the orbit's Fourier truncation on this many harmonics (default: --harmonics); "
                  "shooting costs about the same from any H, so a coarse solve can report many harmonics")
      ->check(CLI::PositiveNumber);
}

orbits::RefinedSolution refine(const HbModel& model, const Eigen::VectorXd& full, const RefineArguments& a) {
  orbits::RefinementOptions options;
  options.restitution = a.restitution;
  options.output_harmonics = a.harmonics;
  return orbits::refineByShooting(model, full, options);
}

HbSolution refinedSummary(const HbModel& model, const orbits::RefinedSolution& refined) {
  HbSolution out = summarize(model, refined.full);
  for (size_t i = 0; i < out.displacements.size(); ++i) out.displacements[i].max_abs = refined.max_abs[i];
  return out;
}

nlohmann::json refinementJson(const orbits::RefinedSolution& refined, const HbSolution& plain, double restitution) {
  nlohmann::json hb_max_abs = nlohmann::json::array(), max_abs = nlohmann::json::array();
  for (const auto& c : plain.displacements) hb_max_abs.push_back(c.max_abs);
  for (int i = 0; i < refined.max_abs.size(); ++i) max_abs.push_back(refined.max_abs[i]);
  nlohmann::json out = {{"method", "shoot"},
                        {"converged", refined.converged},
                        {"period_residual", refined.orbit.period_residual},
                        {"iterations", refined.orbit.iterations},
                        {"flow_evaluations", refined.orbit.flow_evaluations},
                        {"harmonics", refined.basis.count()},
                        {"samples", refined.samples},
                        {"seconds", refined.seconds},
                        {"restitution", restitution},
                        {"hb_max_abs", hb_max_abs},
                        {"max_abs", max_abs}};
  if (!refined.converged) out["failure"] = refined.failure;
  return out;
}

}  // namespace eqhb::cli
