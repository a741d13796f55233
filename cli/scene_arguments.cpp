#include "scene_arguments.h"

#include <algorithm>

#include "representable_number.h"

namespace eqhb::cli {

namespace {
// "w10,w20" -> {"w10", "w20"}; "" -> {} (refused by the library as an empty list).
std::vector<std::string> commaSeparated(const std::string& list) {
  std::vector<std::string> items;
  size_t start = 0;
  while (!list.empty() && start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    items.push_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}
}  // namespace

void addSceneOptions(CLI::App* cmd, SceneArguments& a) {
  cmd->add_option("scene", a.path, "Scene file (problems/*.toml)")->required();
  cmd->add_option("--omega", a.omega, "Forcing frequency ω (overrides harmonic_balance.omega)")
      ->check(representableNumber());
  cmd->add_option("--harmonics", a.harmonics, "Number of harmonics H (odd set: 1,3,..,2H-1; all: 0..H)");
  cmd->add_option("--samples", a.samples,
                  "Time samples N per period (>= 2 k_max + 1; default the scene's, raised in proportion to k_max "
                  "where --harmonics needs more)");
  cmd->add_option("--form", a.form, "Law form, for every law that has it (e.g. minmax, projection, min)");
  cmd->add_option("--formulation", a.formulation,
                  "equality or aft (the force in time from the displacement, projected): for every law that has it");
  cmd->add_option("--rho", a.rho, "Scaling ρ > 0 of every law that has one")->check(representableNumber());
  cmd->add_option("--set", a.overrides, "Override a scene value: PATH=VALUE, e.g. law[0].muN=5");
  cmd->add_option_function<std::string>(
      "--show", [&a](const std::string& list) { a.show = commaSeparated(list); },
      "DOFs the tables, CSV and chart show, by number from 1 or name: e.g. w10,w20 on a beam (default: the "
      "scene's [output] dofs; on beams a few deflections, on more than 8 DOFs four spread to the last, else every "
      "DOF)");
  cmd->add_option_function<std::string>(
      "--peak-dof", [&a](const std::string& dof) { a.peak_dof = dof; },
      "The DOF whose maximum defines a peak, by number or name (default: the scene's [output] peak; on beams the "
      "tip deflection, else the last DOF)");
}

}  // namespace eqhb::cli
