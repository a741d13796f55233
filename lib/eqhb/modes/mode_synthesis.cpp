#include "eqhb/modes/mode_synthesis.h"

#include <cmath>
#include <complex>

#include "eqhb/error.h"

namespace eqhb {

namespace {
using Complex = std::complex<double>;

// x̂₁ = c − i s per DOF, from the point's coefficients [x̂; λ̂].
Eigen::VectorXcd fundamental(const HbModel& model, const Eigen::VectorXd& full) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  int offset = -1;
  for (size_t h = 0; h < model.basis.harmonics().size(); ++h)
    if (model.basis.harmonics()[h] == 1) offset = model.basis.offset(static_cast<int>(h));
  Eigen::VectorXcd x(n);
  for (int i = 0; i < n; ++i) x[i] = Complex(full[i * nb + offset], -full[i * nb + offset + 1]);
  return x;
}

// The two roots Ω² of |ω² − Ω² + 2iζωΩ| = r (header); false when none is
// real and positive.
bool forcingFrequencies(double omega, double zeta, double r, double* lower, double* upper) {
  const double w2 = omega * omega, centre = w2 * (1.0 - 2.0 * zeta * zeta);
  const double discriminant = r * r - 4.0 * zeta * zeta * w2 * w2 * (1.0 - zeta * zeta);
  if (!(discriminant >= 0.0)) return false;
  const double root = std::sqrt(discriminant), low = centre - root, high = centre + root;
  if (!(high > 0.0)) return false;
  *upper = std::sqrt(high);
  *lower = low > 0.0 ? std::sqrt(low) : 0.0;
  return true;
}
}  // namespace

Eigen::VectorXcd synthesisForcing(const HbModel& forced) {
  const LinearStructure& s = forced.structure;
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(s.dofs());
  bool any = false;
  for (const HarmonicLoad& load : s.loads) {
    if (load.harmonic != 1) continue;
    f[load.dof] += Complex(load.cos_amplitude, -load.sin_amplitude);  // F̂ = F_c − i F_s
    any = any || load.cos_amplitude != 0.0 || load.sin_amplitude != 0.0;
  }
  if (!any)
    throwInputError("forcing", "none at harmonic 1",
                    "the synthesis of a forced response needs a forcing at the first harmonic ([[forcing]])");
  return f;
}

ModeSynthesis synthesizeForcedResponse(const HbModel& forced, const Backbone& backbone) {
  const Eigen::VectorXcd force = synthesisForcing(forced);
  ModeSynthesis out;
  std::vector<SynthesisPoint> upper;
  // The peak lies where r(a) = 2ζω²√(1 − ζ²), the root's vanishing: h = (r −
  // that) a changes sign between the last amplitude with a real Ω and the
  // next one up the path, and is interpolated linearly in a there (h is
  // linear in a when the mode does not change with it: a linear structure's
  // peak is exact).
  const BackbonePoint* below = nullptr;
  double h_below = 0.0;
  for (const BackbonePoint& p : backbone.points) {
    if (!p.converged) continue;
    const Eigen::VectorXcd psi = fundamental(forced, p.full) / p.amplitude;
    const double modal_mass = psi.dot(forced.structure.mass * psi).real();  // ψᴴ M ψ
    const double r = std::abs(psi.dot(force)) / (modal_mass * p.amplitude);
    const double h =
        (r - 2.0 * p.damping_ratio * p.omega * p.omega * std::sqrt(1.0 - p.damping_ratio * p.damping_ratio)) * p.amplitude;
    double low = 0.0, high = 0.0;
    if (!forcingFrequencies(p.omega, p.damping_ratio, r, &low, &high)) {
      if (!below && !out.closed) out.peak_below_from = true;
      if (below && !out.closed && p.amplitude > below->amplitude) {
        const double t = h_below / (h_below - h);
        const double omega = below->omega + t * (p.omega - below->omega);
        const double zeta = below->damping_ratio + t * (p.damping_ratio - below->damping_ratio);
        out.peak_amplitude = below->amplitude + t * (p.amplitude - below->amplitude);
        out.peak_omega = omega * std::sqrt(std::max(0.0, 1.0 - 2.0 * zeta * zeta));
        out.peak_max_abs.resize(p.max_abs.size());
        for (size_t j = 0; j < p.max_abs.size(); ++j)
          out.peak_max_abs[j] = below->max_abs[j] + t * (p.max_abs[j] - below->max_abs[j]);
        out.closed = true;
      }
      continue;
    }
    if (!out.closed) {
      out.peak_below_from = false;
      below = &p;
      h_below = h;
      if (p.amplitude > out.peak_amplitude) {
        out.peak_amplitude = p.amplitude;
        out.peak_omega = 0.5 * (low + high);
        out.peak_max_abs = p.max_abs;
      }
    }
    if (low > 0.0) out.points.push_back({low, p.amplitude, false, p.max_abs});
    upper.push_back({high, p.amplitude, true, p.max_abs});
  }
  out.points.insert(out.points.end(), upper.rbegin(), upper.rend());
  return out;
}

}  // namespace eqhb
