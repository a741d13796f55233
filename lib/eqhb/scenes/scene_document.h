// The scene file as a TOML document (scene_document.cpp): what scene.cpp
// and the ρ readers share before a document becomes a Scene.
#pragma once

#include <string>
#include <toml.hpp>

namespace eqhb::scene_reading {

// The text of the scene file at `path`, refused (InputError) when it cannot
// be one: a directory, unreadable, or larger than kMaxSceneBytes.
std::string readSceneText(const std::string& path);

// Applies one `--set PATH=VALUE` assignment (e.g. law[0].muN=5) to `root`;
// InputError naming --set for a malformed path or index.
void applyOverride(toml::value& root, const std::string& assignment);

}  // namespace eqhb::scene_reading
