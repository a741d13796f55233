#include "scene_arguments.h"

#include "representable_number.h"

namespace eqhb::cli {

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
}

}  // namespace eqhb::cli
