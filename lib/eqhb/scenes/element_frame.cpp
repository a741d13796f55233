#include "eqhb/scenes/element_frame.h"

#include <cmath>
#include <stdexcept>

#include "eqhb/error.h"

namespace eqhb {

namespace {
// Directions whose cosine is below this are orthogonal: the scene's rounding
// of a rotated frame (1e-16) passes, a wrong frame (1e-3) does not.
constexpr double kOrthogonalCosine = 1e-9;

std::string text(const Eigen::VectorXd& v) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + formatNumber(v[i]);
  return out + "]";
}
}  // namespace

std::vector<Eigen::VectorXd> elementDirections(const ElementDirections& given, int node_dofs,
                                               const std::string& field, const FieldFailure& fail) {
  auto refuse = [&](const std::string& f, const std::string& value, const std::string& rule) {
    fail(f, value, rule);
    throw std::logic_error("elementDirections: the failure handler returned");
  };
  std::vector<Eigen::VectorXd> out;
  std::vector<std::string> names;
  if (given.normal) {
    out.push_back(*given.normal);
    names.push_back(field + ".normal");
  }
  for (size_t i = 0; i < given.tangents.size(); ++i) {
    out.push_back(given.tangents[i]);
    names.push_back(field + ".tangents[" + std::to_string(i) + "]");
  }
  if (out.empty()) {
    if (node_dofs != 1)
      refuse(field + ".normal", "(missing)",
             "an element between nodes of " + std::to_string(node_dofs) + " DOFs needs its normal and/or tangents");
    return {Eigen::VectorXd::Ones(1)};
  }
  for (size_t a = 0; a < out.size(); ++a) {
    if (out[a].size() != node_dofs)
      refuse(names[a], text(out[a]),
             "must have one entry per DOF of the node (" + std::to_string(node_dofs) + ")");
    const double norm = out[a].norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) refuse(names[a], text(out[a]), "must be a nonzero, finite direction");
    const Eigen::VectorXd unit = out[a] / norm;
    for (size_t b = 0; b < a; ++b)
      if (std::abs(unit.dot(out[b])) > kOrthogonalCosine)
        refuse(names[a], text(out[a]), "must be orthogonal to " + names[b].substr(field.size() + 1));
    out[a] = unit;
  }
  return out;
}

}  // namespace eqhb
