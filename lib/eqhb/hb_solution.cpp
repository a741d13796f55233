#include "eqhb/hb_solution.h"

#include "eqhb/fourier_transform.h"

namespace eqhb {

namespace {
ChannelSummary channel(FourierTransform& transform, double omega, std::string label,
                       const Eigen::VectorXd& coefficients) {
  ChannelSummary c;
  c.label = std::move(label);
  c.coefficients = coefficients;
  c.samples.resize(transform.samples());
  transform.synthesize(coefficients.data(), c.samples.data());
  c.max_abs = c.samples.cwiseAbs().maxCoeff();
  Eigen::VectorXd rate_coefficients(coefficients.size()), rate(transform.samples());
  transform.differentiate(coefficients.data(), omega, rate_coefficients.data());
  transform.synthesize(rate_coefficients.data(), rate.data());
  c.max_abs_rate = rate.cwiseAbs().maxCoeff();
  return c;
}
}  // namespace

HbSolution summarize(const HbModel& model, const Eigen::VectorXd& full) {
  FourierTransform transform(model.basis, model.samples);
  const int nb = model.basis.size();
  HbSolution solution;
  for (int i = 0; i < model.structure.dofs(); ++i)
    solution.displacements.push_back(channel(transform, model.omega, "x" + std::to_string(i + 1),
                                              full.segment(i * nb, nb)));
  const int base = model.structure.dofs() * nb;
  for (size_t l = 0; l < model.laws.size(); ++l)
    for (int a = 0; a < model.laws[l].law->dimension(); ++a) {
      const int q = model.componentIndex(static_cast<int>(l), a);
      std::string label = "law" + std::to_string(l + 1) + ".lambda";
      if (model.laws[l].law->dimension() > 1) label += std::to_string(a + 1);
      solution.forces.push_back(channel(transform, model.omega, label, full.segment(base + q * nb, nb)));
    }
  return solution;
}

}  // namespace eqhb
