#include "eqhb/output/static_state_json.h"

#include <string>

namespace eqhb::output {

nlohmann::json staticStateJson(const HbModel& model, const StaticContactState& state) {
  nlohmann::json out;
  out["converged"] = state.result.converged();
  out["iterations"] = state.result.iterations;
  out["solver"] = state.solver;
  out["failed"] = state.failed;
  out["residual_norm"] = state.result.final_norm;
  out["displacement"] = std::vector<double>(state.displacement.data(), state.displacement.data() + state.displacement.size());
  nlohmann::json elements = nlohmann::json::array();
  for (size_t l = 0; l < model.laws.size(); ++l) {
    nlohmann::json e;
    e["law"] = static_cast<int>(l) + 1;
    e["type"] = model.laws[l].law->type();
    std::vector<double> force;
    for (int a = 0; a < model.laws[l].law->dimension(); ++a)
      force.push_back(state.forces[model.componentIndex(static_cast<int>(l), a)]);
    e["lambda"] = force;
    if (const auto& s = state.status[l]) {
      e["state"] = staticStateName(s->state);
      if (s->gap) e["gap"] = *s->gap;
      if (s->normal_force) e["normal_force"] = *s->normal_force;
      if (s->tangential_force) e["tangential_force"] = *s->tangential_force;
      if (s->friction_limit) e["friction_limit"] = *s->friction_limit;
    }
    elements.push_back(e);
  }
  out["elements"] = elements;
  return out;
}

}  // namespace eqhb::output
