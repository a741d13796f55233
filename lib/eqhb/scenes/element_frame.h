// The directions of an element between two nodes (or one node and the
// ground), as a scene gives them: an optional normal n and tangents t1, t2,
// each with one entry per DOF of the node. The law's components read them in
// the order [n, t1, t2] (those given), on u_a − u_b.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace eqhb {

struct ElementDirections {
  std::optional<Eigen::VectorXd> normal;
  std::vector<Eigen::VectorXd> tangents;
};

// Reports a bad field: (field, value, rule); never returns.
using FieldFailure = std::function<void(const std::string&, const std::string&, const std::string&)>;

// The unit directions in component order. Refused, through `fail` naming
// `field`.normal or `field`.tangents: a zero or non-finite direction, one of
// another length than `node_dofs`, tangents not orthogonal to the normal or to
// each other (|cos| > 1e-9), or none given on a node of more than one DOF (on
// a one-DOF node the direction defaults to [1]).
std::vector<Eigen::VectorXd> elementDirections(const ElementDirections& given, int node_dofs,
                                               const std::string& field, const FieldFailure& fail);

}  // namespace eqhb
