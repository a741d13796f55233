// Law::withScaleFreeRho of the laws whose only scale-free setting is ρ.
#pragma once

#include <memory>

#include "eqhb/laws/law.h"

namespace eqhb {

// For a law of class L with its ρ in the member `rho`, set by `setting`: a
// copy with ρ = factor × the scale-free ρ of compareRho, nullptr when ρ was
// given.
template <class L>
std::shared_ptr<Law> copyWithScaleFreeRho(const L& law, const RhoSetting& setting, double L::*rho,
                                          const LawScales& scales) {
  if (!setting.scale_free) return nullptr;
  auto copy = std::make_shared<L>(law);
  (*copy).*rho = setting.factor * law.compareRho(scales)->scale_free;
  return copy;
}

}  // namespace eqhb
