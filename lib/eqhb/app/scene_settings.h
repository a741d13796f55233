// Which scene a run is on and what is changed in it: the document (a file,
// or a loader for a model built in memory), "PATH=VALUE" overrides, and the
// common settings ω, H, N, form, formulation and ρ that apply to the whole
// scene. Every
// interface (the eqhb command, Python) describes its scene this way, so an
// option that reloads the scene (the ρ candidates of an accuracy target)
// works the same in each.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/laws/law.h"
#include "eqhb/scenes/scene.h"

namespace eqhb::app {

struct SceneSettings {
  std::string path;                    // the scene file (unless `document` is set)
  std::vector<std::string> overrides;  // "PATH=VALUE", e.g. "law[0].muN=5"
  std::optional<double> omega;         // harmonic_balance.omega
  std::optional<int> harmonics;        // H; N is raised in proportion where the scene's is too few
  std::optional<int> samples;          // N
  std::optional<std::string> form;     // every law that has a form
  std::optional<double> rho;           // every law that has ρ, > 0
  // "equality" or "aft", for every law that has that formulation
  // (lawFormulationOverrides, scenes/scene.h).
  std::optional<std::string> formulation;
  // The DOFs the outputs show and the one that defines a peak, by number
  // from 1 or name ("w10"); unset: the scene's [output] or its default
  // (scenes/dof_choice.h).
  std::optional<std::vector<std::string>> show;
  std::optional<std::string> peak_dof;

  // A scene held in memory rather than in `path`: the scene and each law's ρ
  // as its document sets them, with the given overrides applied.
  struct Document {
    std::function<Scene(const std::vector<std::string>& overrides)> load;
    std::function<std::vector<std::optional<RhoSetting>>(const std::vector<std::string>& overrides)> law_rhos;
  };
  std::optional<Document> document;
};

// The scene with every override and setting applied, settled under its
// preload (static_preload.h); throws InputError
// naming the setting ("form", "rho") or the scene's field.
Scene loadScene(const SceneSettings& settings);
// The scene's document with `overrides` only (no common settings).
Scene loadDocument(const SceneSettings& settings, const std::vector<std::string>& overrides);
// Each law's ρ as the document with `overrides` sets it (lawRhos).
std::vector<std::optional<RhoSetting>> documentRhos(const SceneSettings& settings,
                                                    const std::vector<std::string>& overrides);

}  // namespace eqhb::app
