// eqhb generate: writes a chain scene of any size for scaling studies.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "eqhb/scenes/scene_generator.h"

namespace eqhb::cli {

struct GenerateArguments {
  ChainSceneSpec spec;
  std::string out;            // scene file; empty: standard output
  std::string matrix_market;  // folder for M/K/C .mtx files and scene.toml
};

void addGenerateCommand(CLI::App& app, GenerateArguments& a);
int runGenerate(const GenerateArguments& a);

}  // namespace eqhb::cli
