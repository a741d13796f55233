#include "eqhb/harmonic_balance/hb_solution.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "eqhb/harmonic_balance/fourier_transform.h"

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

// summarize runs on every recorded point of a curve and on every point a
// writer prints: its transform is kept (one per thread, FourierTransform is
// not thread-safe) and made again only when the basis or N changes, since
// making an FFTW plan costs more than the summary itself (12 % of an
// arclength sweep of friction-1d).
FourierTransform& summaryTransform(const HarmonicSet& basis, int samples) {
  thread_local std::unique_ptr<FourierTransform> kept;
  if (!kept || kept->samples() != samples || kept->basis().harmonics() != basis.harmonics())
    kept = std::make_unique<FourierTransform>(basis, samples);
  return *kept;
}
}  // namespace

std::string dofLabel(int dof) { return "x" + std::to_string(dof + 1); }

std::string dofLabel(const HbModel& model, int dof) {
  return static_cast<size_t>(dof) < model.dof_names.size() ? model.dof_names[dof] : dofLabel(dof);
}

std::string lawComponentLabel(const HbModel& model, int law, int component) {
  std::string label = "law" + std::to_string(law + 1) + ".lambda";
  if (model.laws[law].law->dimension() > 1) label += std::to_string(component + 1);
  return label;
}

std::vector<std::string> lawComponentLabels(const HbModel& model) {
  std::vector<std::string> labels(model.lawComponents());
  for (size_t l = 0; l < model.laws.size(); ++l)
    for (int a = 0; a < model.laws[l].law->dimension(); ++a)
      labels[model.componentIndex(static_cast<int>(l), a)] = lawComponentLabel(model, static_cast<int>(l), a);
  return labels;
}

HbSolution summarize(const HbModel& model, const Eigen::VectorXd& full) {
  FourierTransform& transform = summaryTransform(model.basis, model.samples);
  const int nb = model.basis.size();
  HbSolution solution;
  for (int i = 0; i < model.structure.dofs(); ++i)
    solution.displacements.push_back(channel(transform, model.omega, dofLabel(model, i),
                                              full.segment(i * nb, nb)));
  const int base = model.structure.dofs() * nb;
  for (size_t l = 0; l < model.laws.size(); ++l)
    for (int a = 0; a < model.laws[l].law->dimension(); ++a) {
      const int q = model.componentIndex(static_cast<int>(l), a);
      solution.forces.push_back(channel(transform, model.omega, lawComponentLabel(model, static_cast<int>(l), a),
                                        full.segment(base + q * nb, nb)));
    }
  return solution;
}

double firstHarmonicAmplitude(const HarmonicSet& basis, const double* c) {
  const auto& ks = basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h)
    if (ks[h] == 1) {
      const int o = basis.offset(static_cast<int>(h));
      return std::hypot(c[o], c[o + 1]);
    }
  return 0.0;
}

Eigen::VectorXd transferCoefficients(const HbModel& from, const HbModel& to, const Eigen::VectorXd& full) {
  const int channels = from.structure.dofs() + from.lawComponents();
  const int nb_from = from.basis.size(), nb_to = to.basis.size();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(channels * nb_to);
  const auto& ks = from.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    if (!to.basis.contains(ks[h])) continue;
    const auto& target = to.basis.harmonics();
    const int t = static_cast<int>(std::lower_bound(target.begin(), target.end(), ks[h]) - target.begin());
    const int width = ks[h] == 0 ? 1 : 2;
    for (int c = 0; c < channels; ++c)
      out.segment(c * nb_to + to.basis.offset(t), width) =
          full.segment(c * nb_from + from.basis.offset(static_cast<int>(h)), width);
  }
  return out;
}

}  // namespace eqhb
