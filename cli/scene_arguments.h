// Options shared by the commands that load a scene: the file, the common
// overrides (--omega, --harmonics, --samples, --form,
// --formulation, --rho), --set and the outputs' --show and --peak-dof,
// read into the application layer's scene settings.
#pragma once

#include <CLI/CLI.hpp>

#include "eqhb/app/scene_settings.h"

namespace eqhb::cli {

using SceneArguments = app::SceneSettings;

void addSceneOptions(CLI::App* command, SceneArguments& args);
// Loads the scene with every override applied; throws InputError.
inline Scene loadSceneWith(const SceneArguments& args) { return app::loadScene(args); }

}  // namespace eqhb::cli
