// Reading a scene's TOML tables: a table reader that names each value by
// its field path and refuses unknown keys, and the helpers every part of
// the scene reader shares (scene.cpp, structure_readers.cpp).
#pragma once

#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <toml.hpp>

#include "eqhb/error.h"
#include "eqhb/scenes/toml_number.h"

namespace eqhb::scene_reading {

inline std::string describe(const toml::value& v) {
  std::ostringstream out;
  out << v;
  std::string text = out.str();
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

// Reads one TOML table, remembering which keys were used, so that unknown
// keys (typos) are reported instead of silently ignored.
class TableReader {
 public:
  TableReader(const toml::value& value, std::string field, std::string source)
      : field_(std::move(field)), source_(std::move(source)) {
    if (!value.is_table()) fail(field_, describe(value), "must be a table");
    table_ = &value.as_table();
  }

  // Every key asked about is one this table allows, present or not: the
  // list shown for an unknown key (a typo) is then the keys allowed here.
  bool has(const std::string& key) const {
    asked_.insert(key);
    return table_->count(key) > 0;
  }

  const toml::value& raw(const std::string& key) {
    used_.insert(key);
    auto it = table_->find(key);
    if (it == table_->end()) fail(path(key), "(missing)", "required");
    return it->second;
  }

  double number(const std::string& key, std::optional<double> fallback = std::nullopt) {
    if (!has(key) && fallback) return *fallback;
    return numberIn(raw(key), path(key), "must be a number");
  }

  // The number `v` holds; `not_number` is the rule when it holds none.
  double numberIn(const toml::value& v, const std::string& field, const std::string& not_number) const {
    double x = 0.0;
    if (v.is_integer()) x = static_cast<double>(v.as_integer());
    else if (v.is_floating()) x = v.as_floating();
    else fail(field, describe(v), not_number);
    const std::string range = floatRangeProblem(v);
    if (!range.empty()) fail(field, tomlLiteral(v), range);
    if (!std::isfinite(x)) fail(field, describe(v), "must be finite (no NaN or Inf)");
    return x;
  }

  // Range-checked before narrowing: TOML integers are 64-bit.
  int integer(const std::string& key, std::optional<int> fallback = std::nullopt,
              int max = std::numeric_limits<int>::max()) {
    if (!has(key) && fallback) return *fallback;
    const toml::value& v = raw(key);
    if (!v.is_integer()) fail(path(key), describe(v), "must be an integer");
    const std::int64_t x = v.as_integer();
    if (x > max) fail(path(key), std::to_string(x), "must be <= " + std::to_string(max));
    if (x < std::numeric_limits<int>::min())
      fail(path(key), std::to_string(x), "must be >= " + std::to_string(std::numeric_limits<int>::min()));
    return static_cast<int>(x);
  }

  std::string text(const std::string& key, std::optional<std::string> fallback = std::nullopt) {
    if (!has(key) && fallback) return *fallback;
    const toml::value& v = raw(key);
    if (!v.is_string()) fail(path(key), describe(v), "must be a string");
    // A file name would end at the NUL when opened: another file than written.
    if (v.as_string().str.find('\0') != std::string::npos)
      fail(path(key), describe(v), "must not contain a NUL character (\\u0000)");
    return v.as_string().str;
  }

  std::vector<double> numbers(const std::string& key) {
    const toml::value& v = raw(key);
    if (!v.is_array() || v.as_array().empty()) fail(path(key), describe(v), "must be a non-empty array of numbers");
    std::vector<double> out;
    for (size_t i = 0; i < v.as_array().size(); ++i)
      out.push_back(numberIn(v.as_array()[i], path(key) + "[" + std::to_string(i) + "]", "must be a number"));
    return out;
  }

  Eigen::MatrixXd matrix(const std::string& key) {
    const toml::value& v = raw(key);
    if (!v.is_array() || v.as_array().empty())
      fail(path(key), describe(v), "must be a non-empty array of rows");
    const auto& rows = v.as_array();
    Eigen::MatrixXd m(rows.size(), rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      if (!rows[i].is_array() || rows[i].as_array().size() != rows.size())
        fail(path(key) + "[" + std::to_string(i) + "]", describe(rows[i]),
             "must be a row of " + std::to_string(rows.size()) + " numbers (square matrix)");
      for (size_t j = 0; j < rows.size(); ++j) {
        m(i, j) = numberIn(rows[i].as_array()[j],
                           path(key) + "[" + std::to_string(i) + "][" + std::to_string(j) + "]",
                           "entries must be numbers");
      }
    }
    return m;
  }

  void requireKnownKeys() const {
    for (const auto& [key, value] : *table_)
      if (!used_.count(key)) {
        std::set<std::string> allowed = asked_;
        allowed.insert(used_.begin(), used_.end());
        std::string known;
        for (const auto& k : allowed) known += (known.empty() ? "" : ", ") + k;
        fail(path(key), describe(value), "unknown key (allowed here: " + known + ")");
      }
  }
  // Marks keys as known without reading them (optional keys of another variant).
  void allow(std::initializer_list<const char*> keys) {
    for (const char* k : keys) used_.insert(k);
  }

  std::string path(const std::string& key) const {
    return field_.empty() ? key : field_ + "." + key;
  }
  [[noreturn]] void fail(const std::string& field, const std::string& value,
                         const std::string& rule) const {
    throw InputError(source_ + ": " + field + " = " + value + ": " + rule);
  }

 private:
  const toml::table* table_ = nullptr;
  std::string field_, source_;
  std::set<std::string> used_;           // keys read: the others present are unknown
  mutable std::set<std::string> asked_;  // keys asked about with has()
};

// [[key]]: an array of tables, else a clear error naming the key.
inline const toml::array& arrayOfTables(TableReader& top, const std::string& key) {
  const toml::value& v = top.raw(key);
  if (!v.is_array()) top.fail(key, describe(v), "must be an array of tables ([[" + key + "]])");
  return v.as_array();
}

// A path in a scene file is relative to the scene file's folder.
inline std::string relativeToScene(const std::string& source, const std::string& path) {
  if (!path.empty() && path[0] == '/') return path;
  const auto slash = source.find_last_of('/');
  return slash == std::string::npos ? path : source.substr(0, slash + 1) + path;
}

// Runs a size check, its message prefixed with the scene's name.
template <typename Check>
void bounded(const std::string& source, Check check) {
  try {
    check();
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
}

}  // namespace eqhb::scene_reading
