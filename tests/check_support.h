// Checks shared by the scene, element and system tests: scene texts edited
// and refused, Jacobians against central differences, scaled residuals,
// turned solutions.
#pragma once

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_support.h"

namespace eqhb::test {

// `text` with its first `from` replaced by `to` (a failure if it has none).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return text;
  return text.replace(at, from.size(), to);
}

// Expects the scene `text`, read as the file `file` with `overrides`, to be
// refused by an InputError whose message contains `needle`.
inline void expectSceneError(const std::string& text, const std::string& needle,
                             const std::vector<std::string>& overrides = {}, const std::string& file = "scene.toml") {
  try {
    parseScene(text, file, overrides);
    ADD_FAILURE() << "accepted; expected an error mentioning " << needle;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

// max |J − J_fd| / (1 + max |J_fd|) at z: the system's weak Jacobian against
// central differences (infinite if the system cannot evaluate it).
inline double jacobianError(SquareSystem& system, const Eigen::VectorXd& z) {
  Eigen::VectorXd g(system.size());
  Eigen::MatrixXd j(system.size(), system.size());
  if (!system.residualAndJacobian(z, g, j)) return INFINITY;
  const Eigen::MatrixXd fd = finiteDifferenceJacobian(system, z);
  return (j - fd).cwiseAbs().maxCoeff() / (1.0 + fd.cwiseAbs().maxCoeff());
}

// ‖g / scales‖ at z: the measure the solvers' residual tolerance bounds
// (infinite if g cannot be formed).
inline double scaledResidualNorm(SquareSystem& system, const Eigen::VectorXd& z) {
  Eigen::VectorXd g(system.size()), scales(system.size());
  if (!system.residual(z, g)) return INFINITY;
  system.residualScales(scales);
  return g.cwiseQuotient(scales).norm();
}

// Of two solutions' coefficients (nb per DOF, DOFs first) on `nodes` nodes
// of 3 DOFs: the largest ‖R x_a − x_b‖ over nodes and coefficients, x the
// node's displacement coefficient: 0 when b is a turned by R.
inline double turnedMismatch(const Eigen::Matrix3d& r, const Eigen::VectorXd& a, const Eigen::VectorXd& b, int nb,
                             int nodes) {
  double worst = 0.0;
  for (int node = 0; node < nodes; ++node)
    for (int t = 0; t < nb; ++t) {
      Eigen::Vector3d xa, xb;
      for (int i = 0; i < 3; ++i) {
        xa[i] = a[(3 * node + i) * nb + t];
        xb[i] = b[(3 * node + i) * nb + t];
      }
      worst = std::max(worst, (r * xa - xb).norm());
    }
  return worst;
}

}  // namespace eqhb::test
