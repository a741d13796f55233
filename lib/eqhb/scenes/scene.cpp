#include "eqhb/scenes/scene.h"
#include "eqhb/scenes/law_rho.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <toml.hpp>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/harmonic_balance/system_memory.h"
#include "eqhb/structures/beam.h"
#include "eqhb/structures/matrix_market.h"
#include "eqhb/structures/node_table.h"
#include "eqhb/scenes/dof_choice.h"
#include "eqhb/scenes/element_frame.h"
#include "eqhb/scenes/load_readers.h"
#include "eqhb/scenes/scene_document.h"
#include "eqhb/scenes/structure_readers.h"
#include "eqhb/scenes/table_reader.h"
#include "eqhb/scenes/toml_guard.h"
#include "eqhb/scenes/toml_number.h"
#include "eqhb/size_limits.h"

namespace eqhb {

namespace {

using scene_reading::applyOverride;
using scene_reading::arrayOfTables;
using scene_reading::bounded;
using scene_reading::readSceneText;
using scene_reading::describe;
using scene_reading::NodeMap;
using scene_reading::ReadStructure;
using scene_reading::TableReader;

// [output] dofs = [7, "w10"], peak = "w10": what the outputs show and the
// DOF that defines a peak (scenes/dof_choice.h); each key optional.
DofChoice readOutputChoice(TableReader& top, const std::string& source, const HbModel& model) {
  DofChoice choice = defaultDofChoice(model);
  if (!top.has("output")) return choice;
  TableReader o(top.raw("output"), "output", source);
  auto token = [&](const toml::value& v, const std::string& field) -> std::string {
    if (v.is_integer()) return std::to_string(v.as_integer());
    if (!v.is_string()) o.fail(field, describe(v), "must be a DOF number (from 1) or name (\"w7\", \"x7\")");
    return v.as_string().str;
  };
  if (o.has("dofs")) {
    const toml::value& v = o.raw("dofs");
    if (!v.is_array()) o.fail("output.dofs", describe(v), "must be an array of DOF numbers or names");
    std::vector<std::string> tokens;
    for (size_t i = 0; i < v.as_array().size(); ++i)
      tokens.push_back(token(v.as_array()[i], "output.dofs[" + std::to_string(i) + "]"));
    bounded(source, [&] { choice.shown = resolveDofs(model, tokens, "output.dofs"); });
  }
  if (o.has("peak")) {
    const std::string peak = token(o.raw("peak"), "output.peak");
    bounded(source, [&] { choice.peak = resolveDof(model, peak, "output.peak"); });
  }
  o.requireKnownKeys();
  return choice;
}

// A law's table as its registered parser reads it (laws/law_table.h).
class SceneLawTable : public LawTable {
 public:
  SceneLawTable(TableReader& reader, const std::string& field, const LawEntry& entry, int components,
                std::string components_key, std::vector<int> dofs, std::string dofs_text)
      : LawTable(field, entry.type, entry.forms, components, std::move(components_key), std::move(dofs)),
        reader_(reader), dofs_text_(std::move(dofs_text)) {}
  bool has(const std::string& key) const override { return reader_.has(key); }
  double number(const std::string& key, std::optional<double> fallback) override {
    return reader_.number(key, fallback);
  }
  std::vector<double> numbers(const std::string& key) override { return reader_.numbers(key); }
  std::string text(const std::string& key, std::optional<std::string> fallback) override {
    return reader_.text(key, std::move(fallback));
  }
  std::string dofsText() const override { return dofs_text_; }
  [[noreturn]] void fail(const std::string& field, const std::string& value, const std::string& rule) const override {
    reader_.fail(field, value, rule);
  }

 private:
  TableReader& reader_;
  std::string dofs_text_;
};

// A list of numbers at `field` (a direction).
Eigen::VectorXd readVector(TableReader& t, const toml::value& v, const std::string& field) {
  if (!v.is_array() || v.as_array().empty()) t.fail(field, describe(v), "must be a non-empty array of numbers");
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.as_array().size()));
  for (size_t i = 0; i < v.as_array().size(); ++i)
    out[static_cast<Eigen::Index>(i)] = t.numberIn(v.as_array()[i], field, "entries must be numbers");
  return out;
}

// An element between two nodes, `between = [a, b]` (or `[a]`: against the
// ground), reading n·(u_a − u_b) along its `normal` and `tangents`
// (element_frame.h). Its direction list, as written, goes to `text`.
LawAttachment readElement(TableReader& t, const std::string& field, const NodeMap& nodes, std::string* text) {
  const std::string key = field + ".between";
  const toml::value& list = t.raw("between");
  if (!list.is_array() || list.as_array().empty() || list.as_array().size() > 2)
    t.fail(key, describe(list), "must be [node, node] or [node] (against the ground)");
  std::vector<std::vector<int>> ends;
  for (const auto& e : list.as_array()) {
    if (!e.is_integer()) t.fail(key, describe(list), "node numbers must be integers");
    const auto number = e.as_integer();
    if (number < 1 || number > nodes.count())
      t.fail(key, std::to_string(number),
             "no such node (the structure has " + std::to_string(nodes.count()) + ", numbered from 1)");
    ends.push_back(nodes.dofsOf(static_cast<int>(number)));
  }
  if (ends.size() == 2 && list.as_array()[0].as_integer() == list.as_array()[1].as_integer())
    t.fail(key, describe(list), "the two nodes must differ");
  if (ends.size() == 2 && ends[0].size() != ends[1].size())
    t.fail(key, describe(list), "the two nodes have different numbers of DOFs");
  ElementDirections given;
  *text = describe(list);
  if (t.has("normal")) {
    given.normal = readVector(t, t.raw("normal"), field + ".normal");
    *text = describe(t.raw("normal"));
  }
  if (t.has("tangents")) {
    const toml::value& v = t.raw("tangents");
    if (!v.is_array() || v.as_array().empty() || v.as_array().size() > 2)
      t.fail(field + ".tangents", describe(v), "must be [[t1...]] or [[t1...], [t2...]]");
    for (size_t i = 0; i < v.as_array().size(); ++i)
      given.tangents.push_back(readVector(t, v.as_array()[i], field + ".tangents[" + std::to_string(i) + "]"));
    *text = describe(v);
  }
  const auto directions = elementDirections(given, static_cast<int>(ends[0].size()), field,
                                            [&](const std::string& f, const std::string& value, const std::string& rule) {
                                              t.fail(f, value, rule);
                                            });
  return LawAttachment::relative(ends[0], ends.size() == 2 ? ends[1] : std::vector<int>(), directions);
}

AttachedLaw readLaw(const toml::value& value, const std::string& field, const std::string& source,
                    int dofs, const NodeMap& node_map) {
  TableReader t(value, field, source);
  const std::string type = t.text("type");
  AttachedLaw attached;
  const LawEntry* entry = findLaw(type);
  if (!entry) t.fail(field + ".type", "\"" + type + "\"", "unknown law (known: " + knownLawTypes() + ")");
  if (t.has("between")) {  // an element between two nodes
    if (t.has("dofs") || t.has("nodes"))
      t.fail(field + ".between", "(and dofs or nodes)", "give between or dofs/nodes, not both");
    std::string text;
    attached.attachment = readElement(t, field, node_map, &text);
    const int d = attached.attachment.dimension();
    SceneLawTable table(t, field, *entry, d, t.has("tangents") ? "tangents" : "normal", {}, text);
    attached.law = parseLaw(*entry, table);
    if (d != attached.law->dimension())
      t.fail(field + ".tangents", text,
             "a " + type + " law reads " + std::to_string(attached.law->dimension()) +
                 " direction(s) between the nodes ([normal, t1, t2], those it has)");
    t.requireKnownKeys();
    return attached;
  }
  const int nodes = node_map.beam_nodes;
  std::vector<int> law_dofs;
  // `dofs` (numbered from 1) or, on a structure with nodes, `nodes`.
  const bool by_node = t.has("nodes");
  if (by_node && t.has("dofs")) t.fail(field + ".nodes", "(and dofs)", "give dofs or nodes, not both");
  if (by_node && nodes == 0)
    t.fail(field + ".nodes", describe(t.raw("nodes")), "this structure has no nodes (only beams have): use dofs");
  const std::string key = by_node ? "nodes" : "dofs";
  const int count = by_node ? nodes : dofs;
  const toml::value& list = t.raw(key);
  if (!list.is_array() || list.as_array().empty())
    t.fail(field + "." + key, describe(list), "must be a non-empty array of " + key + " numbers");
  for (const auto& e : list.as_array()) {
    if (!e.is_integer()) t.fail(field + "." + key, describe(list), "numbers must be integers");
    const auto number = e.as_integer();
    if (number < 1 || number > count)
      t.fail(field + "." + key, std::to_string(number),
             std::string(by_node ? "no such node" : "no such DOF") + " (the structure has " +
                 std::to_string(count) + ", numbered from 1)");
    law_dofs.push_back(by_node ? beamTransverseDof(static_cast<int>(number)) : static_cast<int>(number) - 1);
  }
  SceneLawTable table(t, field, *entry, static_cast<int>(law_dofs.size()), key, law_dofs, describe(list));
  attached.law = parseLaw(*entry, table);
  attached.attachment = LawAttachment(law_dofs);
  if (attached.attachment.dimension() != attached.law->dimension())
    t.fail(field + ".dofs", describe(list),
           "a " + type + " law acts on exactly " + std::to_string(attached.law->dimension()) +
               " DOF(s)");
  t.requireKnownKeys();
  return attached;
}

// [harmonic_balance]: the harmonic set, samples and ω, read first: with them
// the model's size is known from the structure's sizes alone, before the
// structure is built.
void readHarmonicBalance(TableReader& top, const std::string& source, HbModel* model) {
  TableReader hb(top.raw("harmonic_balance"), "harmonic_balance", source);
  const int harmonics = hb.integer("harmonics", std::nullopt, kMaxHarmonics);
  const std::string set = hb.text("set", std::string("odd"));
  if (set != "odd" && set != "all")
    hb.fail("harmonic_balance.set", "\"" + set + "\"", "must be \"odd\" or \"all\"");
  if (set == "odd" && harmonics < 1)
    hb.fail("harmonic_balance.harmonics", std::to_string(harmonics),
            "must be >= 1 for set = \"odd\"");
  if (harmonics < 0) hb.fail("harmonic_balance.harmonics", std::to_string(harmonics), "must be >= 0");
  model->basis = HarmonicSet(HarmonicSet::parseKind(set), harmonics);
  model->samples = hb.integer("samples", std::nullopt, kMaxSamples);
  if (model->samples < model->basis.minimumSamples())
    hb.fail("harmonic_balance.samples", std::to_string(model->samples),
            "must be >= 2 k_max + 1 = " + std::to_string(model->basis.minimumSamples()) +
                " (highest harmonic k_max = " + std::to_string(model->basis.highest()) + ")");
  model->omega = hb.number("omega");
  if (!(model->omega > 0.0))
    hb.fail("harmonic_balance.omega", formatNumber(model->omega), "must be > 0");
  hb.requireKnownKeys();
}

// [sweep]: the range `eqhb sweep` takes by default.
void readSweep(TableReader& top, const std::string& source, Scene* scene) {
  if (!top.has("sweep")) return;
  TableReader sweep(top.raw("sweep"), "sweep", source);
  scene->sweep_from = sweep.number("from");
  scene->sweep_to = sweep.number("to");
  // Either direction: a sweep may run down from above a resonance.
  if (!(*scene->sweep_from > 0.0) || !(*scene->sweep_to > 0.0) || *scene->sweep_to == *scene->sweep_from)
    sweep.fail("sweep", formatNumber(*scene->sweep_from) + ".." + formatNumber(*scene->sweep_to),
               "need from > 0, to > 0 and from != to");
  sweep.requireKnownKeys();
}

// [time_reference]: the time integration's defaults, each key optional.
void readTimeReference(TableReader& top, const std::string& source, TimeReferenceDefaults* defaults) {
  if (!top.has("time_reference")) return;
  TableReader t(top.raw("time_reference"), "time_reference", source);
  t.allow({"step", "theta", "periods", "periodic_tolerance"});
  TimeReferenceDefaults& d = *defaults;
  if (t.has("step")) {
    d.step = t.number("step");
    if (!(*d.step > 0.0)) t.fail("time_reference.step", formatNumber(*d.step), "must be > 0");
  }
  if (t.has("theta")) {
    d.theta = t.number("theta");
    if (!(*d.theta >= 0.5 && *d.theta <= 1.0))
      t.fail("time_reference.theta", formatNumber(*d.theta), "must be in [0.5, 1]");
  }
  if (t.has("periods")) {
    d.periods = t.integer("periods");
    if (*d.periods < 1) t.fail("time_reference.periods", std::to_string(*d.periods), "must be >= 1");
  }
  if (t.has("periodic_tolerance")) {
    d.periodic_tolerance = t.number("periodic_tolerance");
    if (!(*d.periodic_tolerance > 0.0))
      t.fail("time_reference.periodic_tolerance", formatNumber(*d.periodic_tolerance), "must be > 0");
  }
  t.requireKnownKeys();
}

Scene buildScene(toml::value root, const std::string& source, const std::vector<std::string>& overrides) {
  for (const auto& assignment : overrides) applyOverride(root, assignment);
  TableReader top(root, "", source);
  Scene scene;
  scene.source = source;
  scene.name = top.text("name");
  scene.description = top.text("description", std::string());
  readHarmonicBalance(top, source, &scene.model);

  ModelSizes settings;
  settings.coefficients = scene.model.basis.size();
  settings.samples = scene.model.samples;
  const ReadStructure structure = scene_reading::readStructure(top, source, settings);
  scene.model.structure = structure.structure;
  scene.model.dof_names = structure.dof_names;
  const int dofs = scene.model.structure.dofs();

  scene_reading::readForcing(top, source, structure.nodes, &scene.model);
  scene_reading::readPreload(top, source, structure.nodes, &scene.model, &scene.preload);
  if (top.has("law")) {
    const auto& laws = arrayOfTables(top, "law");
    for (size_t i = 0; i < laws.size(); ++i)
      scene.model.laws.push_back(readLaw(laws[i], "law[" + std::to_string(i) + "]", source, dofs,
                                         NodeMap{dofs, structure.nodes, &structure.node_table}));
  }
  readSweep(top, source, &scene);
  readTimeReference(top, source, &scene.time_reference);
  scene.output = readOutputChoice(top, source, scene.model);
  top.allow({"forcing", "preload", "law"});
  top.requireKnownKeys();
  try {
    scene.model.validate();
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  return scene;
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& source_name,
                 const std::vector<std::string>& overrides) {
  checkTomlText(text, source_name);
  toml::value root;
  try {
    std::istringstream in(text);
    root = toml::parse(in, source_name);
  } catch (const std::exception& e) {
    throw InputError(std::string("malformed scene file: ") + e.what());
  }
  return buildScene(std::move(root), source_name, overrides);
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  return parseScene(readSceneText(path), path, overrides);
}

}  // namespace eqhb
