// The scene file as a TOML document, before it becomes a Scene: its text
// read with a size bound, `--set PATH=VALUE` overrides applied to it, the
// per-law overrides the CLI and Python write for a scene (form, ρ,
// formulation), and each law's ρ setting as the document gives it.
#include "eqhb/scenes/scene_document.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <toml.hpp>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/scenes/law_rho.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/scenes/toml_guard.h"
#include "eqhb/size_limits.h"

namespace eqhb {
namespace scene_reading {

std::string readSceneText(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw InputError(path + ": is a directory, not a scene file");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the scene file");
  // Read in chunks up to one byte more than a scene may have: enough to
  // refuse a larger file (or an endless device) without reading it whole,
  // and without clearing 16 MiB for a scene of a few hundred bytes (which
  // cost every command several milliseconds per read).
  std::string text;
  char chunk[1 << 16];
  while (text.size() <= kMaxSceneBytes && file) {
    const size_t want = std::min(sizeof chunk, kMaxSceneBytes + 1 - text.size());
    file.read(chunk, static_cast<std::streamsize>(want));
    text.append(chunk, static_cast<size_t>(file.gcount()));
  }
  if (file.bad()) throw InputError(path + ": cannot read the scene file");
  if (text.size() > kMaxSceneBytes)
    throw InputError(path + ": larger than " + std::to_string(kMaxSceneBytes) + " bytes: not a scene file");
  return text;
}

namespace {

// The value of a --set assignment as TOML reads it; a bare word is a string.
toml::value parseOverrideValue(const std::string& text) {
  checkTomlText(text, "--set");
  try {
    std::istringstream in("v = " + text);
    return toml::find(toml::parse(in, "--set"), "v");
  } catch (const std::exception&) {
    return toml::value(text);  // a bare word: take it as a string
  }
}

}  // namespace

void applyOverride(toml::value& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throwInputError("--set", "\"" + assignment + "\"", "must be PATH=VALUE, e.g. law[0].muN=5");
  const std::string path = assignment.substr(0, eq);
  const toml::value value = parseOverrideValue(assignment.substr(eq + 1));
  toml::value* node = &root;
  std::istringstream segments(path);
  std::string segment;
  std::vector<std::string> parts;
  while (std::getline(segments, segment, '.')) parts.push_back(segment);
  for (size_t p = 0; p < parts.size(); ++p) {
    std::string key = parts[p];
    std::optional<size_t> index;
    const auto bracket = key.find('[');
    if (bracket != std::string::npos) {
      if (key.back() != ']') throwInputError("--set", path, "malformed index in \"" + key + "\"");
      try {
        index = std::stoul(key.substr(bracket + 1, key.size() - bracket - 2));
      } catch (...) {
        throwInputError("--set", path, "malformed index in \"" + key + "\"");
      }
      key = key.substr(0, bracket);
    }
    if (!node->is_table()) throwInputError("--set", path, "\"" + key + "\" is not inside a table");
    auto& table = node->as_table();
    const bool last = p + 1 == parts.size();
    if (last && !index) {
      table[key] = value;
      return;
    }
    auto it = table.find(key);
    if (it == table.end()) {
      if (index) throwInputError("--set", path, "no array \"" + key + "\" to index");
      table[key] = toml::table{};
      it = table.find(key);
    }
    node = &it->second;
    if (node->is_array()) {
      auto& array = node->as_array();
      if (!index && array.size() == 1) index = 0;
      if (!index)
        throwInputError("--set", path, "\"" + key + "\" has " + std::to_string(array.size()) +
                                           " entries: give an index, e.g. " + key + "[0]");
      if (*index >= array.size())
        throwInputError("--set", path, "index " + std::to_string(*index) + " out of range (" +
                                           std::to_string(array.size()) + " entries)");
      node = &array[*index];
      if (last) {
        *node = value;
        return;
      }
    } else if (index) {
      throwInputError("--set", path, "\"" + key + "\" is not an array");
    }
  }
}

}  // namespace scene_reading

using scene_reading::applyOverride;
using scene_reading::readSceneText;

std::vector<std::string> lawOverrides(const HbModel& model, const std::string& key, const std::string& value) {
  std::vector<std::string> out;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const LawEntry& entry = lawEntry(*model.laws[l].law);
    const bool takes = key == "form" ? entry.hasForm(value) : key == "rho" && entry.takesRho();
    if (!takes) continue;
    const std::string quoted = key == "form" ? "\"" + value + "\"" : value;
    out.push_back("law[" + std::to_string(l) + "]." + key + "=" + quoted);
  }
  return out;
}

std::vector<std::string> lawFormulationOverrides(const HbModel& model, const std::string& formulation) {
  if (formulation != "equality" && formulation != "aft")
    throwInputError("formulation", "\"" + formulation + "\"", "must be equality or aft");
  const auto has = [&](const LawEntry& e) { return formulation == "aft" ? bool(e.parse_aft) : bool(e.parse); };
  std::vector<std::string> out;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const LawEntry* entry = findLaw(model.laws[l].law->type());
    if (entry && has(*entry)) out.push_back("law[" + std::to_string(l) + "].formulation=\"" + formulation + "\"");
  }
  if (out.empty()) {
    std::string with;
    for (const LawEntry& e : lawRegistry())
      if (has(e)) with += (with.empty() ? "" : ", ") + e.type;
    throwInputError("formulation", formulation, "no law of the scene has this formulation (laws with it: " + with + ")");
  }
  return out;
}

namespace {
// Each law's ρ in the document `text` with `overrides`, which loads as
// `model` (a law in its AFT form has none).
std::vector<std::optional<RhoSetting>> documentRhos(const std::string& text, const std::string& source,
                                                    const std::vector<std::string>& overrides, const HbModel& model) {
  const size_t laws = model.laws.size();
  toml::value root;
  std::istringstream in(text);
  root = toml::parse(in, source);
  for (const auto& assignment : overrides) applyOverride(root, assignment);
  std::vector<std::optional<RhoSetting>> out;
  if (!root.is_table() || root.as_table().count("law") == 0) return out;
  auto number = [](const toml::value& v) {
    return v.is_integer() ? static_cast<double>(v.as_integer()) : v.as_floating();
  };
  for (const auto& law : root.at("law").as_array()) {
    const std::string type = toml::find<std::string>(law, "type");
    std::optional<RhoSetting> rho;
    if (findLaw(type)->takesRho() && out.size() < laws && !inAftForm(*model.laws[out.size()].law)) {
      const auto& table = law.as_table();
      if (table.count("rho")) rho = RhoSetting(number(law.at("rho")));
      else rho = RhoSetting::scaleFree(table.count("rho_factor") ? number(law.at("rho_factor")) : 1.0);
    }
    out.push_back(rho);
  }
  if (out.size() != laws) throw std::logic_error("lawRhos: laws miscounted");
  return out;
}
}  // namespace

std::vector<std::optional<RhoSetting>> lawRhos(const std::string& path, const std::vector<std::string>& overrides) {
  // Validated as a whole first: the document below is then well formed.
  const Scene scene = loadScene(path, overrides);
  return documentRhos(readSceneText(path), path, overrides, scene.model);
}

std::vector<std::optional<RhoSetting>> lawRhosOfText(const std::string& text, const std::string& source,
                                                     const std::vector<std::string>& overrides) {
  const Scene scene = parseScene(text, source, overrides);
  return documentRhos(text, source, overrides, scene.model);
}

std::string scaledRhoOverride(int l, const RhoSetting& setting, double factor) {
  return "law[" + std::to_string(l) + "]." + setting.field() + "=" + formatNumber(setting.value * factor);
}

}  // namespace eqhb
