#include "eqhb/harmonic_balance/problem_scales.h"

#include <algorithm>
#include <cmath>

#include "eqhb/harmonic_balance/dynamic_stiffness_factors.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

PhysicalScales physicalScales(const HbModel& model, double response) {
  const LinearStructure& s = model.structure;
  double force = 0.0, length = std::isfinite(response) ? std::abs(response) : 0.0;
  for (const auto& load : s.loads) force = std::max(force, std::hypot(load.cos_amplitude, load.sin_amplitude));
  for (const auto& attached : model.laws) {
    force = std::max(force, std::abs(attached.law->forceLevel()));
    length = std::max(length, std::abs(attached.law->displacementLevel()));
  }
  const double w = model.omega;
  double stiffness = 0.0;
  for (const auto& attached : model.laws)
    for (int i : attached.dofs)
      if (i >= 0 && i < s.dofs())
        stiffness = std::max({stiffness, std::abs(s.stiffness.coeff(i, i)), w * std::abs(s.damping.coeff(i, i)),
                              w * w * std::abs(s.mass.coeff(i, i))});
  PhysicalScales scales;
  if (!(force > 0.0) && !(length > 0.0)) return scales;  // all 1: nothing sets a scale
  if (!(force > 0.0)) force = stiffness * length;
  if (!(length > 0.0) && stiffness > 0.0) length = force / stiffness;
  if (!(force > 0.0) || !(length > 0.0) || !std::isfinite(force) || !std::isfinite(length) || !(w > 0.0))
    return PhysicalScales{};
  scales.force = force;
  scales.displacement = length;
  scales.velocity = w * length;
  return scales;
}

double linearResponseAtLaws(const HbModel& model, bool sparse) {
  if (model.structure.loads.empty() || model.laws.empty()) return 0.0;
  const int n = model.structure.dofs(), nb = model.basis.size();
  const Eigen::VectorXd f = forcingCoefficients(model);
  DynamicStiffnessFactors factors(model.structure, model.basis, sparse);
  factors.factorize(model.structure, model.omega);
  double most = 0.0;
  const auto& ks = model.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int w = ks[h] == 0 ? 1 : 2, o = model.basis.offset(static_cast<int>(h));
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(w * n, 1);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) rhs(r * n + i, 0) = f[i * nb + o + r];
    if (rhs.isZero(0.0)) continue;
    const Eigen::MatrixXd x = factors.solve(static_cast<int>(h), rhs);
    for (const auto& attached : model.laws)
      for (int i : attached.dofs)
        most = std::max(most, w == 1 ? std::abs(x(i, 0)) : std::hypot(x(i, 0), x(n + i, 0)));
  }
  return most;
}

}  // namespace eqhb
