#include "py_model.h"

#include <cmath>
#include <memory>

#include "eqhb/error.h"
#include "eqhb/scenes/law_rho.h"
#include "eqhb/structures/structure_matrices.h"
#include "matrix_argument.h"

namespace eqhb::python {

PyModel modelFromScene(const std::string& path, const std::vector<std::string>& overrides) {
  PyModel m{loadScene(path, overrides), {}};
  m.settings.path = path;
  m.settings.overrides = overrides;
  return m;
}

PyModel modelFromText(const std::string& text, const std::string& source) {
  PyModel m{parseScene(text, source), {}};
  m.settings.path = source;
  m.settings.document = app::SceneSettings::Document{
      [text, source](const std::vector<std::string>& o) { return parseScene(text, source, o); },
      [text, source](const std::vector<std::string>& o) { return lawRhosOfText(text, source, o); }};
  return m;
}

PyModel modelFromArrays(const std::string& text, const py::object& mass, const py::object& stiffness,
                        const py::object& damping) {
  StructureMatrices matrices;
  matrices.mass = matrixArgument(mass, "mass");
  matrices.stiffness = matrixArgument(stiffness, "stiffness");
  if (damping.is_none()) {
    matrices.damping.resize(matrices.mass.rows(), matrices.mass.cols());
  } else {
    matrices.damping = matrixArgument(damping, "damping");
  }
  checkStructureMatrices(matrices, 1e-12, MatrixNames{});
  // The document with overrides, its chain replaced by the arrays.
  auto structure = std::make_shared<const LinearStructure>(toLinearStructure(matrices));
  auto load = [text, structure](const std::vector<std::string>& overrides) {
    Scene scene = parseScene(text, "model", overrides);
    LinearStructure arrays = *structure;
    arrays.loads = scene.model.structure.loads;
    scene.model.structure = std::move(arrays);
    scene.model.validate();
    scene.output = defaultDofChoice(scene.model);  // of the arrays, not of the document's placeholder chain
    return scene;
  };
  PyModel m{load({}), {}};
  m.settings.path = "model";
  m.settings.document = app::SceneSettings::Document{
      load, [text](const std::vector<std::string>& o) { return lawRhosOfText(text, "model", o); }};
  return m;
}

app::SceneSettings sceneSettings(const PyModel& m, std::optional<double> omega, std::optional<int> harmonics,
                                 std::optional<int> samples, const std::optional<std::string>& form,
                                 std::optional<double> rho, const std::optional<std::string>& formulation) {
  if (omega && !(std::isfinite(*omega) && *omega > 0)) throwInputError("omega", formatNumber(*omega), "must be > 0");
  if (rho && !(std::isfinite(*rho) && *rho > 0)) throwInputError("rho", formatNumber(*rho), "must be > 0");
  app::SceneSettings s = m.settings;
  s.omega = omega;
  s.harmonics = harmonics;
  s.samples = samples;
  s.form = form;
  s.rho = rho;
  s.formulation = formulation;
  return s;
}

HbModel withSettings(const HbModel& base, std::optional<double> omega, std::optional<int> harmonics,
                     std::optional<int> samples) {
  HbModel model = base;
  if (omega) model.omega = *omega;
  if (harmonics && !samples) model.samples = samplesForHarmonics(model, *harmonics);
  if (harmonics) model.basis = HarmonicSet(model.basis.kind(), *harmonics);
  if (samples) model.samples = *samples;
  if (omega && !(std::isfinite(*omega) && *omega > 0)) throwInputError("omega", formatNumber(*omega), "must be > 0");
  model.validate();
  return model;
}

}  // namespace eqhb::python
