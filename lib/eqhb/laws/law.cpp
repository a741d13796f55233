#include "eqhb/laws/law.h"

namespace eqhb {

void LawSamples::resize(int samples, int dimension, int history_terms) {
  history_sample.setConstant(samples, dimension * dimension * history_terms, kPeriodMean);
  history_weight.setZero(samples, dimension * dimension * history_terms);
  displacement.setZero(samples, dimension);
  velocity.setZero(samples, dimension);
  force.setZero(samples, dimension);
  force_rate.setZero(samples, dimension);
  psi.setZero(samples, dimension);
  dpsi_ddisplacement.setZero(samples, dimension * dimension);
  dpsi_dvelocity.setZero(samples, dimension * dimension);
  dpsi_dforce.setZero(samples, dimension * dimension);
  dpsi_dforce_rate.setZero(samples, dimension * dimension);
}

double Law::residualScale(const PhysicalScales& scales, int) const { return scales.force; }

std::shared_ptr<Law> Law::withScaleFreeRho(const LawScales&) const { return nullptr; }

std::optional<Law::RhoComparison> Law::compareRho(const LawScales&) const { return std::nullopt; }

std::optional<WidthComparison> Law::compareWidth(const LawScales&) const { return std::nullopt; }

}  // namespace eqhb

namespace eqhb {

StaticStatus frictionStatus(double force, double limit) {
  StaticStatus s;
  s.state = limit > 0.0 && force < (1.0 - 1e-8) * limit ? StaticStatus::State::kStuck : StaticStatus::State::kSlipping;
  s.tangential_force = force;
  s.friction_limit = limit;
  return s;
}

const char* staticStateName(StaticStatus::State state) {
  switch (state) {
    case StaticStatus::State::kOpen: return "open";
    case StaticStatus::State::kClosed: return "closed";
    case StaticStatus::State::kStuck: return "stuck";
    case StaticStatus::State::kSlipping: return "slipping";
  }
  return "?";
}

}  // namespace eqhb
