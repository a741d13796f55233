// The static state of a normal contact (StaticStatus, law.h) from its rest
// sample: open or closed by its normal force, shared by the contact laws.
#pragma once

#include "eqhb/laws/law.h"

namespace eqhb {

// `gap0` the contact's initial gap; the rest state's displacement closes it.
inline StaticStatus normalContactStatus(double gap0, const LawSamples& rest) {
  StaticStatus s;
  s.gap = gap0 - rest.displacement(0, 0);
  s.normal_force = rest.force(0, 0);
  s.state = *s.normal_force > 0.0 ? StaticStatus::State::kClosed : StaticStatus::State::kOpen;
  return s;
}

}  // namespace eqhb
