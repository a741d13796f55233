#include "eqhb/orbits/orbit_refinement.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "eqhb/error.h"
#include "eqhb/orbits/flow_dynamics.h"
#include "eqhb/orbits/smooth_flow.h"

namespace eqhb::orbits {

namespace {

// Aliasing of the trapezoidal rule folds harmonic k ± S onto k: with the
// displacement's coefficients falling as k^-3 (friction) or k^-2 (impacts)
// that is (8 k_max)^-3 or ^-2 relative, below the truncation error (k_max^-2,
// k_max^-1) by 500 k_max or 64 times. Each instant costs a phase
// exponential: more instants would only cost time.
int defaultSamples(const HarmonicSet& basis) { return std::max(256, 8 * basis.highest()); }

// λ of every law component from the displacement coefficients x (FullSystem
// layout, first n channels) by the linear dynamics of each harmonic.
void forcesFromDynamics(const HbModel& model, Eigen::VectorXd* full) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  const auto& harmonics = model.basis.harmonics();
  for (size_t h = 0; h < harmonics.size(); ++h) {
    const int k = harmonics[h], o = model.basis.offset(static_cast<int>(h)), width = k == 0 ? 1 : 2;
    Eigen::VectorXd x(width * n), f = Eigen::VectorXd::Zero(width * n);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < width; ++c) x[c * n + i] = (*full)[i * nb + o + c];
    for (const HarmonicLoad& load : model.structure.loads) {
      if (load.harmonic != k) continue;
      f[load.dof] += load.cos_amplitude;
      if (width == 2) f[n + load.dof] += load.sin_amplitude;
    }
    const Eigen::VectorXd unbalanced = model.structure.harmonicOperator(k, model.omega) * x - f;
    for (size_t l = 0; l < model.laws.size(); ++l) {
      const Law& law = *model.laws[l].law;
      for (int a = 0; a < law.dimension(); ++a) {
        const int q = model.componentIndex(static_cast<int>(l), a), dof = model.laws[l].attachment.dof(a);
        for (int c = 0; c < width; ++c) (*full)[(n + q) * nb + o + c] = law.forceSign() * unbalanced[c * n + dof];
      }
    }
  }
}

}  // namespace

HarmonicSet RefinementOptions::outputBasis(const HbModel& model) const {
  return output_harmonics ? HarmonicSet(model.basis.kind(), output_harmonics) : model.basis;
}

void RefinementOptions::validate(const HbModel& model) const {
  shooting.validate();
  if (!(restitution >= 0.0 && restitution <= 1.0))
    throwInputError("restitution", formatNumber(restitution), "must be in [0, 1]");
  if (output_harmonics < 0)
    throwInputError("output_harmonics", std::to_string(output_harmonics), "must be >= 0");
  const HarmonicSet basis = outputBasis(model);
  if (samples != 0 && samples < basis.minimumSamples())
    throwInputError("samples", std::to_string(samples),
                    "must be 0 (automatic) or >= 2 k_max + 1 = " + std::to_string(basis.minimumSamples()));
  // The forces are read off the dynamics on the law's DOFs: two laws on one
  // DOF could not be told apart.
  requireGroundedLaws(model.laws, "exact orbits (shooting)");
  std::set<int> used;
  for (const auto& attached : model.laws)
    for (int dof : attached.attachment.dofs())
      if (!used.insert(dof).second)
        throwInputError("law dofs", std::to_string(dof + 1),
                        "two laws act on this DOF: their forces cannot be refined by shooting");
}

bool projectOrbit(const HbModel& model, const Flow& flow, const ShootingResult& orbit, int samples,
                  Eigen::VectorXd* full) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  const double period = flow.period(), t0 = orbit.start_time;
  FlowSamples at;
  at.times.resize(samples);
  for (int s = 0; s < samples; ++s) at.times[s] = t0 + period * s / samples;
  if (!flow.integrate(orbit.state, t0, period, false, &at).ok) return false;
  *full = Eigen::VectorXd::Zero((n + model.lawComponents()) * nb);
  // Trapezoidal rule over one period (any start: the integrand is periodic).
  const auto& harmonics = model.basis.harmonics();
  for (size_t h = 0; h < harmonics.size(); ++h) {
    const int k = harmonics[h], o = model.basis.offset(static_cast<int>(h));
    const double weight = (k == 0 ? 1.0 : 2.0) / samples;
    for (int s = 0; s < samples; ++s) {
      const double phase = k * model.omega * at.times[s], c = std::cos(phase), sn = std::sin(phase);
      for (int i = 0; i < n; ++i) {
        (*full)[i * nb + o] += weight * c * at.displacement(s, i);
        if (k != 0) (*full)[i * nb + o + 1] += weight * sn * at.displacement(s, i);
      }
    }
  }
  forcesFromDynamics(model, full);
  return true;
}

RefinedSolution refineByShooting(const HbModel& model, const Eigen::VectorXd& full, const RefinementOptions& options) {
  options.validate(model);
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<Flow> flow = makeFlow(model, options.restitution);
  RefinedSolution out;
  out.orbit = shootFromHarmonicBalance(*flow, model, full, options.shooting);
  HbModel output = model;
  output.basis = options.outputBasis(model);
  output.samples = std::max(output.samples, output.basis.minimumSamples());
  out.basis = output.basis;
  out.samples = options.samples ? options.samples : defaultSamples(output.basis);
  if (!out.orbit.converged) {
    out.failure = "shooting did not converge: " + out.orbit.failure;
  } else if (!projectOrbit(output, *flow, out.orbit, out.samples, &out.full)) {
    out.failure = "the flow failed while sampling the orbit";
  } else {
    out.converged = true;
    out.max_abs = out.orbit.max_abs;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace eqhb::orbits
