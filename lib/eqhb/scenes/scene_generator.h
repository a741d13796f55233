// Scene generator for scaling studies: a chain of any size with Coulomb
// friction contacts spread along it, written as scene-file text (inline
// parametric chain, or Matrix Market files beside the scene).
//
// Chain: n masses m joined by springs k and dashpots d, fixed before DOF 1
// and free after DOF n (scene type "chain"), forced at DOF n with
// force cos ωt; contact c (0..C−1) sits on DOF round((c + 1) n / C).
// Contacts are rigid Coulomb friction, or elastic dry friction (a Jenkins
// slider behind a tangential stiffness k_t, in its alternating
// frequency–time form) when k_t is given. A preload is a static force at
// DOF n, solved first (the field's bolted-joint sequence: static state, then
// harmonics 0..H about it); it needs the harmonic set "all".
#pragma once

#include <optional>
#include <string>

namespace eqhb {

struct ChainSceneSpec {
  int dofs = 100;
  int contacts = 5;
  double m = 1.0, k = 1.0, d = 0.02;
  double force = 1.0;
  double mu_n = 0.2;           // friction limit of every contact
  std::optional<double> k_t;   // elastic dry friction of that stiffness; none: rigid Coulomb
  double preload = 0.0;        // static force at DOF n ([[preload]]); 0: none
  int harmonics = 10;          // H
  std::string set = "odd";     // "odd": 1..2H−1, "all": 0..H
  int samples = 0;             // 0: smallest power of two >= 4 k_max + 1 (at least 64)
  double omega = 0.0;          // 0: 0.8 × the chain's first eigenfrequency
};

// The first eigenfrequency of the fixed–free chain: 2 sqrt(k/m) sin(π / (2(2n+1))).
double chainFirstFrequency(const ChainSceneSpec& spec);

// Throws InputError naming the field for sizes that cannot be built
// (dofs < 1, contacts < 0 or > dofs, non-positive parameters, a preload
// without the harmonic set "all").
void validateChainSpec(const ChainSceneSpec& spec);

// Scene text with [structure] type = "chain".
std::string chainSceneText(const ChainSceneSpec& spec);

// Writes M.mtx, K.mtx, C.mtx and scene.toml (type = "matrix-market") into
// `directory` (created if missing); returns the scene path.
std::string writeChainMatrixMarketScene(const ChainSceneSpec& spec, const std::string& directory);

}  // namespace eqhb
