// The table of one law in a scene file ([[law]], scenes/scene.h) as the law's
// parser reads it: typed reads whose keys are remembered (so that a key no
// parser asked for is reported as unknown), and failures that name the field,
// its value and the rule. The scene reader implements the reads over TOML;
// the laws never see the file format.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eqhb/laws/law.h"

namespace eqhb {

class LawTable {
 public:
  // `field`: "law[i]", the prefix of every field a message names; `type`
  // and `forms`: the law's registered name and forms (law_registry.h);
  // `components`: how many components the scene gives the law (its
  // dimension), under the key `components_key` ("dofs", "nodes" or, for an
  // element between nodes, "tangents"); `dofs`: the law's DOFs, 0-based, one
  // per component, for a grounded law (empty for an element between nodes).
  LawTable(std::string field, std::string type, std::vector<std::string> forms, int components,
           std::string components_key, std::vector<int> dofs)
      : field_(std::move(field)), type_(std::move(type)), forms_(std::move(forms)), components_(components),
        components_key_(std::move(components_key)), dofs_(std::move(dofs)) {}
  virtual ~LawTable() = default;

  // Whether the key is present; every key asked about is one the table allows.
  virtual bool has(const std::string& key) const = 0;
  // A finite number; `fallback` when absent (nullopt: the key is required).
  virtual double number(const std::string& key, std::optional<double> fallback) = 0;
  // A required non-empty list of finite numbers.
  virtual std::vector<double> numbers(const std::string& key) = 0;
  // A string; `fallback` when absent (nullopt: the key is required).
  virtual std::string text(const std::string& key, std::optional<std::string> fallback) = 0;
  // The DOF, node or direction list as written, for messages about it.
  virtual std::string dofsText() const = 0;
  // Throws InputError "SOURCE: FIELD = VALUE: RULE".
  [[noreturn]] virtual void fail(const std::string& field, const std::string& value, const std::string& rule) const = 0;

  const std::string& field() const { return field_; }
  int components() const { return components_; }
  const std::string& componentsKey() const { return components_key_; }
  const std::vector<int>& dofs() const { return dofs_; }
  std::string path(const std::string& key) const { return field_ + "." + key; }

  // Reads shared by the laws, each with its message:
  // a number > 0 ("must be > 0");
  double positive(const std::string& key, std::optional<double> fallback);
  // the same, nullopt when absent (a constant the law then sets scale-free);
  std::optional<double> optionalPositive(const std::string& key);
  // a required friction limit >= 0 ("friction limit must be >= 0");
  double frictionLimit(const std::string& key);
  // ρ: `rho` in the problem's units or, without it, scale-free with
  // `rho_factor` (1 by default), never both, > 0 (Law's RhoSetting);
  RhoSetting rho();
  // `form`, one of the law's registered forms (`fallback` when absent).
  std::string form(const std::string& fallback);

 private:
  std::string field_, type_;
  std::vector<std::string> forms_;
  int components_;
  std::string components_key_;
  std::vector<int> dofs_;
};

}  // namespace eqhb
