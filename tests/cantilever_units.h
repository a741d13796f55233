// NLvib's cantilever with dry friction (problems/cantilever-friction-si.toml,
// SI) posed in other systems of units, for tests that one problem in any
// units is one problem.
#pragma once

#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "eqhb/backends/registry.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace test {

// A unit system: its length, time and force units in metres, seconds and newtons.
struct Units {
  const char* name;
  double length, time, force;
  // Time and force units powers of two: the same solve bit for bit (a
  // length unit would not be: it scales a beam's translations and not its
  // rotations, so LU pivoting may choose other rows).
  bool binary;
};

// SI; mm/N/ms; powers of two; nondimensional (length 2 m, the free first
// mode's 1/ω as time, the friction limit 1.5 N as force).
inline const std::vector<Units>& unitSystems() {
  static const std::vector<Units> all = {{"SI", 1.0, 1.0, 1.0, true},
                                         {"mm/N/ms", 1e-3, 1e-3, 1.0, false},
                                         {"time 1/128 s, force 4 N", 1.0, 1.0 / 128.0, 4.0, true},
                                         {"nondimensional", 2.0, 1.0 / 123.34, 1.5, false}};
  return all;
}

// Every digit of `value` (a TOML number).
inline std::string exactNumber(double value) {
  std::ostringstream out;
  out << std::setprecision(17) << value;
  return out.str();
}

// The scene's parameters in `u` as overrides (appended to `set`), solved at
// omega_si (rad/s) and swept over its [sweep] range 370 -> 110 rad/s.
inline std::vector<std::string> cantileverInUnits(const Units& u, double omega_si, std::vector<std::string> set = {}) {
  const double x = u.length, t = u.time, f = u.force;
  const double mass = f * t * t / x;  // the unit of mass, in kg
  auto put = [&](const std::string& key, double value) { set.push_back(key + "=" + exactNumber(value)); };
  put("structure.E", 185e9 * x * x / f);
  put("structure.I", 2.5e-5 / (x * x * x * x));
  put("structure.rhoA", 234.9 * x / mass);
  put("structure.L", 2.0 / x);
  set.push_back("structure.rayleigh=[0.0, " + exactNumber(8.033e-5 / t) + "]");
  put("forcing[0].cos", 0.2 / f);
  put("law[0].muN", 1.5 / f);
  put("harmonic_balance.omega", omega_si * t);
  put("sweep.from", 370.0 * t);
  put("sweep.to", 110.0 * t);
  return set;
}

// One dogleg solve from zero of the scene in `u` at omega_si with `set`.
struct UnitsOutcome {
  SolverResult result;
  double contact = 0.0;      // max|x| at the contact's DOF, in metres
  std::shared_ptr<Law> law;  // the law as the system used it (scale-free constants set)
};
inline UnitsOutcome solveCantileverIn(const Units& u, double omega_si, std::vector<std::string> set = {}) {
  const Scene scene = loadScene(problem("cantilever-friction-si.toml"), cantileverInUnits(u, omega_si, std::move(set)));
  auto system = makeHbSystem(scene.model, true);
  UnitsOutcome o;
  o.result = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
  const int dof = scene.model.laws[0].attachment.dof(0);
  o.contact = summarize(scene.model, system->fullCoefficients(o.result.solution)).displacements[dof].max_abs * u.length;
  o.law = system->model().laws[0].law;
  return o;
}

}  // namespace test
}  // namespace eqhb
