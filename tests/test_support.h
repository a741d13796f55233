// Helpers shared by the tests: finite-difference Jacobians and models.
#pragma once

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/joints/contact_friction.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/solvers/square_system.h"
#include "eqhb/backends/registry.h"

namespace eqhb::test {

// Whether a backend was compiled in (CMake options EQHB_WITH_*).
inline bool registered(const std::string& name);

inline std::string problem(const std::string& file) {
  return std::string(EQHB_PROBLEMS_DIR) + "/" + file;
}

// The message of the InputError `f` throws; "(no error)" if it throws none.
inline std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// A shipped scene (with `set` overrides) solved from rest on the condensed or
// full system: its model, the solver's result and [x; λ].
struct SolvedScene {
  HbModel model;
  SolverResult result;
  Eigen::VectorXd full;
};
inline SolvedScene solveFromRest(const std::string& file, const std::vector<std::string>& set = {},
                                 bool condensed = true, const std::string& solver = "dogleg") {
  SolvedScene s;
  s.model = loadScene(problem(file), set).model;
  const auto system = makeHbSystem(s.model, condensed);
  s.result = makeSolver(solver)->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
  s.full = system->fullCoefficients(s.result.solution);
  return s;
}

// A contact with friction on `tangential` DOFs: μ = 0.4, preload 0.7, gap
// 0.2, a compliant normal of stiffness 3; the rest ContactFriction's defaults.
inline ContactFrictionParameters contactFrictionParameters(int tangential, NormalForm normal, FrictionForm friction,
                                                           std::optional<double> k_t = std::nullopt) {
  ContactFrictionParameters p;
  p.tangential = tangential;
  p.mu = 0.4;
  p.preload = 0.7;
  p.gap = 0.2;
  p.normal = normal;
  if (normal == NormalForm::kCompliant) p.normal_stiffness = 3.0;
  p.friction = friction;
  p.tangential_stiffness = k_t;
  return p;
}

// Central differences of system at z, step h.
inline Eigen::MatrixXd finiteDifferenceJacobian(SquareSystem& system, const Eigen::VectorXd& z,
                                                double h = 1e-7) {
  const int n = system.size();
  Eigen::MatrixXd j(n, n);
  Eigen::VectorXd plus(n), minus(n), zp = z, zm = z;
  for (int c = 0; c < n; ++c) {
    zp[c] += h;
    zm[c] -= h;
    system.residual(zp, plus);
    system.residual(zm, minus);
    j.col(c) = (plus - minus) / (2 * h);
    zp[c] = zm[c] = z[c];
  }
  return j;
}

// The 2-DOF chain of the spec (m = k = 1, d = 0.02, f1 = 20 cos ωt), Coulomb on DOF 2.
inline HbModel chainWithFriction(double mu_n, CoulombForm form, int harmonics, double omega,
                                 int samples = 256, HarmonicKind kind = HarmonicKind::kOdd) {
  HbModel model;
  Eigen::MatrixXd t(2, 2);
  t << 2, -1, -1, 1;
  model.structure = LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd::Identity(2, 2), t, 0.02 * t);
  model.structure.loads.push_back({0, 1, 20.0, 0.0});
  model.laws.push_back({{1}, std::make_shared<Coulomb1D>(mu_n, form, 1.0, 5.0)});
  model.basis = HarmonicSet(kind, harmonics);
  model.samples = samples;
  model.omega = omega;
  return model;
}

// Den Hartog's oscillator: m ẍ + k x + F sgn(ẋ) = P cos ωt with m = k = P = 1
// (no damping), F = `friction`, on odd harmonics.
inline HbModel denHartog(double omega, double friction, int harmonics, int samples) {
  HbModel model;
  model.structure = LinearStructure::fromMassStiffnessDamping(
      Eigen::MatrixXd::Identity(1, 1), Eigen::MatrixXd::Identity(1, 1), Eigen::MatrixXd::Zero(1, 1));
  model.structure.loads.push_back({0, 1, 1.0, 0.0});
  model.laws.push_back({{0}, std::make_shared<Coulomb1D>(friction, CoulombForm::kMinMax)});
  model.basis = HarmonicSet(HarmonicKind::kOdd, harmonics);
  model.samples = samples;
  model.omega = omega;
  return model;
}

// Den Hartog (1931): X / x_st = sqrt(V² − β² U²), V = 1/(1 − r²), U = tan(π/(2r))/r.
inline double denHartogAmplitude(double r, double beta) {
  const double v = 1.0 / (1.0 - r * r), u = std::tan(M_PI / (2.0 * r)) / r;
  return std::sqrt(v * v - beta * beta * u * u);
}

// A harmonic-balance solution [x; λ] of `model` (own dogleg, condensed, from
// zero, |g| <= 1e-10), expected to converge.
inline Eigen::VectorXd harmonicBalance(const HbModel& model) {
  auto system = makeHbSystem(model, true);
  SolverOptions options;
  options.residual_tolerance = 1e-10;
  const auto result = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), options);
  EXPECT_TRUE(result.converged());
  return system->fullCoefficients(result.solution);
}

inline bool registered(const std::string& name) {
  for (const auto& entry : registeredSolvers())
    if (entry.name == name) return true;
  return false;
}

}  // namespace eqhb::test
