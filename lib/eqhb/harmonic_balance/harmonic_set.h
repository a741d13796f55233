// The truncated Fourier basis of the weighted-residual formulation (spec §3)
// with H harmonics: 0, 1, .., H ("all", constant included) or the first H odd
// ones 1, 3, .., 2H−1 ("odd", the spec's "H = 10 odd (1..19)"). Each k > 0
// contributes cos(kωt) and sin(kωt), k = 0 the constant.
//
// Coefficient layout of one channel (one DOF or one force component), used
// everywhere in the library: for each harmonic k in increasing order, one
// coefficient if k = 0, else the pair (cos, sin).
#pragma once

#include <string>
#include <vector>

namespace eqhb {

enum class HarmonicKind { kAll, kOdd };

class HarmonicSet {
 public:
  // count H >= 0 (kAll) or >= 1 (kOdd); throws InputError otherwise.
  HarmonicSet(HarmonicKind kind, int count);

  HarmonicKind kind() const { return kind_; }
  // H, the number of non-constant harmonics.
  int count() const { return count_; }
  // k_max: H (all) or 2H − 1 (odd).
  int highest() const { return highest_; }
  const std::vector<int>& harmonics() const { return harmonics_; }
  // Number of basis functions of one channel.
  int size() const { return size_; }
  // Offset of harmonic number `index` (into harmonics()) inside a channel.
  int offset(int index) const { return offsets_[index]; }
  bool contains(int k) const;
  // Smallest sample count that resolves the basis without aliasing: 2 k_max + 1.
  int minimumSamples() const { return 2 * highest_ + 1; }

  static HarmonicKind parseKind(const std::string& name);  // "all" | "odd"
  static std::string kindName(HarmonicKind kind);

 private:
  HarmonicKind kind_;
  int count_;
  int highest_;
  int size_ = 0;
  std::vector<int> harmonics_;
  std::vector<int> offsets_;
};

// Coefficients of harmonic k in one channel: 1 for the constant, else 2 (cos, sin).
inline int harmonicWidth(int k) { return k == 0 ? 1 : 2; }

}  // namespace eqhb
