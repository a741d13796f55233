// A model as Python holds it: the scene (for its properties, sweeps and
// stability) and how to load it again with settings (app::SceneSettings),
// so that eqhb.solve, shoot, simulate and compare run the application layer
// exactly as the eqhb command does.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "eqhb/app/scene_settings.h"
#include "eqhb/scenes/scene.h"

namespace eqhb::python {

namespace py = pybind11;

struct PyModel {
  Scene scene;
  app::SceneSettings settings;  // the document, no common settings
};

PyModel modelFromScene(const std::string& path, const std::vector<std::string>& overrides);
PyModel modelFromText(const std::string& text, const std::string& source);
// The model of `text` (a scene document whose structure only fixes the DOF
// count) with M, K and C (None: no damping) from arrays, in the order of
// eqhb.model; the loads and laws come from the text.
PyModel modelFromArrays(const std::string& text, const py::object& mass, const py::object& stiffness,
                        const py::object& damping);

// The model's settings with ω, H, N, form, ρ and formulation of one call.
app::SceneSettings sceneSettings(const PyModel& model, std::optional<double> omega, std::optional<int> harmonics,
                                 std::optional<int> samples, const std::optional<std::string>& form = std::nullopt,
                                 std::optional<double> rho = std::nullopt,
                                 const std::optional<std::string>& formulation = std::nullopt);

// The model with another ω, H or N, validated (sweeps and stability).
HbModel withSettings(const HbModel& base, std::optional<double> omega, std::optional<int> harmonics,
                     std::optional<int> samples);

}  // namespace eqhb::python
