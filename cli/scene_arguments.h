// Options shared by the commands that load a scene: the file, the common
// overrides (--omega, --harmonics, --samples, --form, --rho) and --set.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/scenes/scene.h"

namespace eqhb::cli {

struct SceneArguments {
  std::string scene;
  std::optional<double> omega, rho;
  std::optional<int> harmonics, samples;
  std::optional<std::string> form;
  std::vector<std::string> overrides;  // --set
};

void addSceneOptions(CLI::App* command, SceneArguments& args);
// Loads the scene with every override applied; throws InputError.
Scene loadSceneWith(const SceneArguments& args);

}  // namespace eqhb::cli
