#include "bench_studies.h"

#include <algorithm>
#include <utility>

#include "bench_progress.h"
#include "eqhb/backends/registry.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/scenes/scene.h"

namespace fs = std::filesystem;

namespace eqhb::bench {

namespace {

// A formulation of a scene: its label in the tables and the scene overrides
// that make it.
using Formulation = std::pair<std::string, std::vector<std::string>>;

bool isBuilt(const std::vector<std::string>& built, const std::string& name) {
  if (name == kDefaultPath) return true;
  return std::find(built.begin(), built.end(), name) != built.end();
}

// The forms of the scene's first law ({""} where it has none).
std::vector<std::string> firstLawForms(const Scene& base) {
  if (!base.model.laws.empty() && !lawEntry(*base.model.laws[0].law).forms.empty())
    return lawEntry(*base.model.laws[0].law).forms;
  return {""};
}

// (label, overrides) per formulation: each form of the first law's type;
// for contact-friction also each normal form with the max friction form
// (the scenes' own is projection).
std::vector<Formulation> sceneFormulations(const Scene& base, bool quick) {
  std::vector<std::string> forms = firstLawForms(base);
  if (quick) forms.resize(1);
  std::vector<Formulation> formulations;
  for (const auto& form : forms)
    formulations.push_back({form.empty() ? "-" : form,
                            form.empty() ? std::vector<std::string>{} : lawOverrides(base.model, "form", form)});
  if (!quick && !base.model.laws.empty() && base.model.laws[0].law->type() == "contact-friction")
    for (const auto& form : forms) {
      std::vector<std::string> set = lawOverrides(base.model, "form", form);
      for (size_t l = 0; l < base.model.laws.size(); ++l)
        if (base.model.laws[l].law->type() == "contact-friction")
          set.push_back("law[" + std::to_string(l) + "].friction_form=\"max\"");
      formulations.push_back({form + ", friction max", set});
    }
  return formulations;
}

// Variants of the default formulation: ρ an order of magnitude off its
// default, and twice the harmonics.
std::vector<Formulation> sceneVariants(const Scene& base) {
  const std::vector<std::string> forms = firstLawForms(base);
  const std::string default_form = forms[0].empty() ? "-" : forms[0];
  std::vector<Formulation> variants;
  for (const char* rho : {"0.1", "10"}) {
    const auto set = lawOverrides(base.model, "rho", rho);
    if (!set.empty()) variants.push_back({default_form + ", rho=" + rho, set});
  }
  const int h2 = 2 * base.model.basis.count();
  variants.push_back({default_form, {"harmonic_balance.harmonics=" + std::to_string(h2),
                                     "harmonic_balance.samples=" + std::to_string(std::max(base.model.samples, 16 * h2))}});
  return variants;
}

// The scene at `path` in each formulation, on both systems, by each built
// backend of `backends`; the scene is number `scene_index` of `scene_count`.
void runFormulations(const std::string& study, const fs::path& path, const std::vector<Formulation>& formulations,
                     const std::vector<std::string>& backends, const std::vector<std::string>& built,
                     const BenchOptions& options, const Truth& truth, ProgressLine& line, size_t scene_index,
                     size_t scene_count, std::vector<Case>& cases) {
  for (const auto& [form, set] : formulations)
    for (bool condensed : {true, false})
      for (const auto& name : backends) {
        if (!isBuilt(built, name)) continue;
        Case c = runCase(study, path, set, name, condensed, options.repeats, 2.0, &truth);
        c.form = form;
        if (study == "variants")
          note(line, cat("  ", c.scene, " H=", c.harmonics, " ", c.form, " ", c.system, " ", name, ": ", c.termination));
        else
          note(line, cat("  ", c.scene, " ", c.form, " ", c.system, " ", name, ": ", c.termination, " ",
                         c.median_seconds, " s"));
        line.update(static_cast<double>(scene_index) / scene_count, count("scene", scene_index + 1, scene_count),
                    c.scene + " " + c.form + " " + name);
        cases.push_back(c);
      }
}

}  // namespace

SceneLists listScenes(const std::string& problems) {
  SceneLists lists;
  std::vector<fs::path>& scenes = lists.small;
  for (const auto& entry : fs::directory_iterator(problems))
    if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  // Structures with many DOFs (beams, finite-element models) are measured in
  // the scale study; the per-scene tables compare formulations and backends
  // on the small scenes, where a time-domain reference is affordable.
  scenes.erase(std::remove_if(scenes.begin(), scenes.end(),
                              [&](const fs::path& path) {
                                const bool large = loadScene(path.string()).model.structure.dofs() > 20;
                                if (large) lists.structures.push_back(path);
                                return large;
                              }),
               scenes.end());
  return lists;
}

std::vector<std::string> builtBackends() {
  std::vector<std::string> built;
  for (const auto& e : registeredSolvers()) built.push_back(e.name);
  return built;
}

std::vector<Case> runBackendStudy(const BenchOptions& options, const std::vector<std::string>& built) {
  std::vector<Case> cases;
  const fs::path friction = fs::path(options.problems) / "friction-1d.toml";
  if (!fs::exists(friction)) return cases;
  const std::vector<int> hs = options.quick ? std::vector<int>{10} : std::vector<int>{10, 40};
  ProgressLine line(cli::verbosity().progress, "bench 1/5 backends");
  const size_t total = hs.size() * 2 * built.size();
  for (int h : hs)
    for (bool condensed : {true, false})
      for (const auto& name : built) {
        Case c = runCase("backends", friction, {"harmonic_balance.harmonics=" + std::to_string(h)}, name, condensed,
                         options.repeats, 5.0, nullptr);
        c.form = "minmax";
        cases.push_back(c);
        note(line, cat("  backends H=", h, " ", c.system, " ", name, ": ", c.termination));
        line.update(static_cast<double>(cases.size()) / total, count("case", cases.size(), total));
      }
  line.finish();
  return cases;
}

void runSceneStudy(const BenchOptions& options, const std::vector<fs::path>& scenes,
                   const std::vector<std::string>& built, std::vector<Case>& cases, std::vector<TruthStatus>& truths) {
  const std::vector<std::string> scene_backends =
      options.quick ? std::vector<std::string>{"dogleg", "dogleg-newton", "minpack"}
                    : std::vector<std::string>{"dogleg", "dogleg-newton", "minpack", "ceres-lm", "ceres-dogleg",
                                               "ipopt-ls", "ipopt-square", "nlopt-slsqp", kDefaultPath};
  const std::vector<std::string> variant_backends = {"dogleg", "dogleg-newton", "minpack", "ipopt-ls"};
  ProgressLine line(cli::verbosity().progress, "bench 2/5 scenes");
  for (const auto& path : scenes) {
    const size_t scene_index = &path - scenes.data();
    line.update(static_cast<double>(scene_index) / scenes.size(), count("scene", scene_index + 1, scenes.size()),
                path.stem().string());
    const Scene base = loadScene(path.string());
    const Truth truth = buildTruth(path, options.reference_step, options.quick ? 40 : 200);
    truths.push_back(truthStatus(truth));
    runFormulations("scenes", path, sceneFormulations(base, options.quick), scene_backends, built, options, truth,
                    line, scene_index, scenes.size(), cases);
    if (options.quick) continue;
    runFormulations("variants", path, sceneVariants(base), variant_backends, built, options, truth, line,
                    scene_index, scenes.size(), cases);
  }
  line.finish(std::to_string(cases.size()) + " cases");
}

}  // namespace eqhb::bench
