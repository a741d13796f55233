// What both harmonic-balance systems share (hb_systems.h): the forcing's
// coefficients, the residual's scales, the physics check of a converged
// solution, the scale-free ρ; and the choice between them. FullSystem is in
// full_system.cpp, CondensedSystem in condensed_system.cpp.
#include "eqhb/harmonic_balance/hb_systems.h"

#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/laws/dissipation_deficit.h"

namespace eqhb {

Eigen::VectorXd forcingCoefficients(const HbModel& model) {
  const HarmonicSet& basis = model.basis;
  const int nb = basis.size();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model.structure.dofs() * nb);
  const auto& ks = basis.harmonics();
  for (const auto& load : model.structure.loads) {
    for (size_t h = 0; h < ks.size(); ++h) {
      if (ks[h] != load.harmonic) continue;
      const int o = load.dof * nb + basis.offset(static_cast<int>(h));
      f[o] += load.cos_amplitude;
      if (load.harmonic != 0) f[o + 1] += load.sin_amplitude;
    }
  }
  return f;
}

HbSystem::HbSystem(HbModel model, const std::function<void(const HbModel&)>& fits)
    : model_((model.validate(), fits(model), withScaleFreeRhos(std::move(model)))), laws_(model_), nb_(model_.basis.size()) {}

void HbSystem::residualScales(Eigen::Ref<Eigen::VectorXd> scales) const {
  const PhysicalScales physical = physicalScales(model_, responseAtLaws());
  const int law_rows = model_.lawComponents() * nb_, first_law_row = size() - law_rows;
  scales.head(first_law_row).setConstant(physical.force);  // full system: A x − f − W λ
  for (int l = 0; l < static_cast<int>(model_.laws.size()); ++l)
    for (int a = 0; a < model_.laws[l].law->dimension(); ++a)
      scales.segment(first_law_row + model_.componentIndex(l, a) * nb_, nb_)
          .setConstant(model_.laws[l].law->residualScale(physical, a));
}

double HbSystem::unknownScale() const {
  const PhysicalScales physical = physicalScales(model_, responseAtLaws());
  return condensed() ? physical.force : std::hypot(physical.displacement, physical.force);
}

std::string HbSystem::violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) {
  Eigen::VectorXd g(size());
  if (!residual(z, g)) return "";  // not finite: the solver's verdict already refused it
  const PhysicalScales physical = physicalScales(model_, responseAtLaws());
  for (int l = 0; l < laws_.lawCount(); ++l)
    for (const auto& [name, value] : laws_.violations(l, physical))
      if (name == "dissipation_deficit" && !(value < kGrossDissipationDeficit)) {
        // A regularised form's width far off the contact's slip velocities is the usual cause.
        const std::string width = widthScaleAdvice(model_, l);
        return "law[" + std::to_string(l) + "] (" + model_.laws[l].law->type() + ") dissipates too little: " +
               name + " = " + formatNumber(value) + " (0 when the friction force opposes the slip at its limit)" +
               (width.empty() ? "" : "; " + width);
      }
  return "";
}

void HbSystem::setScaleFreeRhos() {
  if (rho_held_) return;
  // Each returns the model as it was when no ρ is scale-free.
  model_ = rho_static_ ? withStaticScaleFreeRhos(std::move(model_)) : withScaleFreeRhos(std::move(model_));
  laws_.replaceLaws(model_.laws);
}

void HbSystem::scaleRhoByStaticCompliance() {
  rho_static_ = true;
  setScaleFreeRhos();
}

std::unique_ptr<HbSystem> makeHbSystem(const HbModel& model, bool condensed, LinearAlgebra algebra,
                                       const Deadline& deadline) {
  if (condensed) return std::make_unique<CondensedSystem>(model, algebra, deadline);
  return std::make_unique<FullSystem>(model, deadline);
}

}  // namespace eqhb
