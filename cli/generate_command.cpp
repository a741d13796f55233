#include "generate_command.h"

#include <fstream>
#include <iostream>

#include "eqhb/error.h"

namespace eqhb::cli {

void addGenerateCommand(CLI::App& app, GenerateArguments& a) {
  auto* cmd = app.add_subcommand("generate", "Write a chain scene of any size (scaling studies)");
  cmd->add_option("--dofs", a.spec.dofs, "Number of masses (DOFs)")->capture_default_str();
  cmd->add_option("--contacts", a.spec.contacts, "Coulomb friction contacts spread along the chain")->capture_default_str();
  cmd->add_option("--harmonics", a.spec.harmonics, "H (odd harmonics 1..2H-1)")->capture_default_str();
  cmd->add_option("--set", a.spec.set, "Harmonic set: odd (1..2H-1) or all (0..H)")->capture_default_str();
  cmd->add_option("--samples", a.spec.samples, "N (0: a power of two >= 4 k_max + 1)")->capture_default_str();
  cmd->add_option("--omega", a.spec.omega, "Frequency (0: 0.8 x the first eigenfrequency)")->capture_default_str();
  cmd->add_option("--mu-n", a.spec.mu_n, "Friction limit of every contact")->capture_default_str();
  cmd->add_option("--k-t", a.spec.k_t, "Elastic dry friction: tangential stiffness before each slider (default: rigid Coulomb)");
  cmd->add_option("--preload", a.spec.preload, "Static force at the last DOF, solved first (needs --set all)")
      ->capture_default_str();
  cmd->add_option("--force", a.spec.force, "Amplitude of the cosine force at the last DOF")->capture_default_str();
  cmd->add_option("--m", a.spec.m, "Mass of each DOF")->capture_default_str();
  cmd->add_option("--k", a.spec.k, "Spring stiffness")->capture_default_str();
  cmd->add_option("--d", a.spec.d, "Dashpot coefficient")->capture_default_str();
  cmd->add_option("--out", a.out, "Scene file to write (default: standard output)");
  cmd->add_option("--matrix-market", a.matrix_market,
                  "Write M.mtx, K.mtx, C.mtx and scene.toml (type = matrix-market) into this folder");
}

int runGenerate(const GenerateArguments& a) {
  if (!a.matrix_market.empty()) {
    if (!a.out.empty()) throwInputError("--out", a.out, "not with --matrix-market (the scene is FOLDER/scene.toml)");
    std::cout << writeChainMatrixMarketScene(a.spec, a.matrix_market) << "\n";
    return 0;
  }
  const std::string text = chainSceneText(a.spec);
  if (a.out.empty()) {
    std::cout << text;
    return 0;
  }
  std::ofstream file(a.out);
  file << text;
  if (!file) throw InputError(a.out + ": cannot write the scene file");
  return 0;
}

}  // namespace eqhb::cli
