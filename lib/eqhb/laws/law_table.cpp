#include "eqhb/laws/law_table.h"

#include <algorithm>

#include "eqhb/error.h"

namespace eqhb {

double LawTable::positive(const std::string& key, std::optional<double> fallback) {
  const double x = number(key, fallback);
  if (!(x > 0.0)) fail(path(key), formatNumber(x), "must be > 0");
  return x;
}

std::optional<double> LawTable::optionalPositive(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return positive(key, std::nullopt);
}

double LawTable::frictionLimit(const std::string& key) {
  const double x = number(key, std::nullopt);
  if (x < 0.0) fail(path(key), formatNumber(x), "friction limit must be >= 0");
  return x;
}

RhoSetting LawTable::rho() {
  if (has("rho") && has("rho_factor"))
    fail(path("rho_factor"), formatNumber(number("rho_factor", std::nullopt)), "give rho or rho_factor, not both");
  const std::string key = has("rho") ? "rho" : "rho_factor";
  const double x = number(key, 1.0);
  if (!(x > 0.0)) fail(path(key), formatNumber(x), "must be > 0");
  return has("rho") ? RhoSetting(x) : RhoSetting::scaleFree(x);
}

std::string LawTable::form(const std::string& fallback) {
  const std::string name = text("form", fallback);
  if (std::find(forms_.begin(), forms_.end(), name) == forms_.end()) {
    std::string list;
    for (const auto& f : forms_) list += (list.empty() ? "" : ", ") + f;
    fail(path("form"), "\"" + name + "\"", "a " + type_ + " law has forms " + list);
  }
  return name;
}

}  // namespace eqhb
