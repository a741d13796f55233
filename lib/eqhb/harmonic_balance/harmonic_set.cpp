#include "eqhb/harmonic_balance/harmonic_set.h"

#include <algorithm>

#include "eqhb/error.h"
#include "eqhb/size_limits.h"

namespace eqhb {

HarmonicSet::HarmonicSet(HarmonicKind kind, int count) : kind_(kind), count_(count), highest_(0) {
  if (kind == HarmonicKind::kOdd && count < 1)
    throwInputError("harmonics", std::to_string(count), "an odd harmonic set needs H >= 1");
  if (count < 0) throwInputError("harmonics", std::to_string(count), "must be >= 0");
  if (count > kMaxHarmonics)
    throwInputError("harmonics", std::to_string(count), "must be <= " + std::to_string(kMaxHarmonics));
  highest_ = kind == HarmonicKind::kOdd ? 2 * count - 1 : count;
  const int first = kind == HarmonicKind::kOdd ? 1 : 0;
  const int stride = kind == HarmonicKind::kOdd ? 2 : 1;
  for (int k = first; k <= highest_; k += stride) {
    harmonics_.push_back(k);
    offsets_.push_back(size_);
    size_ += k == 0 ? 1 : 2;
  }
}

bool HarmonicSet::contains(int k) const {
  return std::binary_search(harmonics_.begin(), harmonics_.end(), k);
}

HarmonicKind HarmonicSet::parseKind(const std::string& name) {
  if (name == "all") return HarmonicKind::kAll;
  if (name == "odd") return HarmonicKind::kOdd;
  throwInputError("harmonic set", "\"" + name + "\"", "must be \"all\" or \"odd\"");
}

std::string HarmonicSet::kindName(HarmonicKind kind) {
  return kind == HarmonicKind::kOdd ? "odd" : "all";
}

}  // namespace eqhb
