#include "eqhb/harmonic_balance/invariants.h"

#include <exception>

#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/sparse_matrix.h"

namespace eqhb {

PhysicalScales invariantScales(const HbModel& model) {
  double response = 0.0;
  try {
    response = linearResponseAtLaws(model, model.structure.dofs() >= kSparseCondensationFromDofs);
  } catch (const std::exception&) {
    // singular at this ω: the scales fall back on the loads and stiffness, as for convergence
  }
  return physicalScales(model, response);
}

std::vector<LawInvariants> checkInvariants(const HbModel& model, const Eigen::VectorXd& full,
                                           int samples) {
  return checkInvariants(model, full, invariantScales(model), samples);
}

std::vector<LawInvariants> checkInvariants(const HbModel& model, const Eigen::VectorXd& full,
                                           const PhysicalScales& scales, int samples) {
  const int n = samples > 0 ? samples : 8 * model.samples;
  FourierTransform transform(model.basis, n);
  const int nb = model.basis.size();
  const int base = model.structure.dofs() * nb;
  Eigen::VectorXd rate(nb), reading(nb);  // reading: u_a = W_a x, coefficients
  std::vector<LawInvariants> reports;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const AttachedLaw& attached = model.laws[l];
    const int d = attached.law->dimension();
    LawSamples s;
    s.resize(n, d);
    for (int a = 0; a < d; ++a) {
      attached.attachment.gatherCoefficients(full.data(), nb, a, reading.data());
      const double* x = reading.data();
      transform.synthesize(x, s.displacement.col(a).data());
      transform.differentiate(x, model.omega, rate.data());
      transform.synthesize(rate.data(), s.velocity.col(a).data());
      const int q = model.componentIndex(static_cast<int>(l), a);
      transform.synthesize(full.data() + base + q * nb, s.force.col(a).data());
      transform.differentiate(full.data() + base + q * nb, model.omega, rate.data());
      transform.synthesize(rate.data(), s.force_rate.col(a).data());
    }
    reports.push_back({static_cast<int>(l), attached.law->type(), attached.law->violations(s, scales)});
  }
  return reports;
}

}  // namespace eqhb
