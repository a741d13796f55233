// A law's forms and their names in one table: the name of a form, and the
// form of a name, an unknown name being an InputError that names the field
// and lists the forms ("must be a, b or c" unless a rule is given).
#pragma once

#include <cstddef>
#include <string>
#include <utility>

#include "eqhb/error.h"

namespace eqhb {

template <class Form>
using FormName = std::pair<Form, const char*>;

template <class Form, std::size_t N>
std::string formName(const FormName<Form> (&names)[N], Form form) {
  for (const auto& [f, name] : names)
    if (f == form) return name;
  return "?";
}

template <class Form, std::size_t N>
Form parseForm(const FormName<Form> (&names)[N], const std::string& name, const std::string& field,
               std::string rule = "") {
  for (const auto& [f, n] : names)
    if (name == n) return f;
  if (rule.empty()) {
    rule = "must be ";
    for (std::size_t i = 0; i < N; ++i) rule += (i == 0 ? "" : i + 1 < N ? ", " : " or ") + std::string(names[i].second);
  }
  throwInputError(field, "\"" + name + "\"", rule);
}

}  // namespace eqhb
