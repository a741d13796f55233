#include "eqhb/structures/beam.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

HermiteBlocks hermiteBeamBlocks(double l) {
  return {{{12, 6 * l, -12, 6 * l},
           {6 * l, 4 * l * l, -6 * l, 2 * l * l},
           {-12, -6 * l, 12, -6 * l},
           {6 * l, 2 * l * l, -6 * l, 4 * l * l}},
          {{156, 22 * l, 54, -13 * l},
           {22 * l, 4 * l * l, 13 * l, -3 * l * l},
           {54, 13 * l, 156, -22 * l},
           {-13 * l, -3 * l * l, -22 * l, 4 * l * l}}};
}

StructureMatrices cantileverBeam(const BeamParameters& beam) {
  if (beam.elements < 1) throwInputError("structure.elements", std::to_string(beam.elements), "must be >= 1");
  auto positive = [](const char* field, double x) {
    if (!(x > 0.0) || !std::isfinite(x)) throwInputError(field, formatNumber(x), "must be finite and > 0");
  };
  positive("structure.E", beam.youngs_modulus);
  positive("structure.I", beam.second_moment);
  positive("structure.rhoA", beam.mass_per_length);
  positive("structure.L", beam.length);
  const int n = 2 * beam.elements;
  const double l = beam.length / beam.elements;
  const double ei = beam.youngs_modulus * beam.second_moment / (l * l * l);
  const double ra = beam.mass_per_length * l / 420.0;
  const HermiteBlocks blocks = hermiteBeamBlocks(l);
  std::vector<Eigen::Triplet<double>> k, m;
  k.reserve(16 * beam.elements);
  m.reserve(16 * beam.elements);
  for (int e = 0; e < beam.elements; ++e) {
    // Element e joins node e (the clamp when e = 0) and node e + 1.
    const int first = 2 * (e - 1);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int i = first + a, j = first + b;
        if (i < 0 || j < 0) continue;  // clamped DOFs
        k.emplace_back(i, j, ei * blocks.stiffness[a][b]);
        m.emplace_back(i, j, ra * blocks.mass[a][b]);
      }
  }
  return fromElementTriplets(n, m, k);
}

std::vector<double> cantileverFrequencies(const BeamParameters& beam, int count) {
  std::vector<double> omegas;
  const double scale = std::sqrt(beam.youngs_modulus * beam.second_moment /
                                 (beam.mass_per_length * std::pow(beam.length, 4)));
  for (int r = 1; r <= count; ++r) {
    // Root of f(x) = cos x cosh x + 1 near (2r − 1) π / 2, by Newton.
    double x = (2 * r - 1) * M_PI / 2;
    if (r == 1) x = 1.875;
    for (int it = 0; it < 50; ++it) {
      const double f = std::cos(x) * std::cosh(x) + 1.0;
      const double df = -std::sin(x) * std::cosh(x) + std::cos(x) * std::sinh(x);
      const double step = f / df;
      x -= step;
      if (std::abs(step) < 1e-15 * x) break;
    }
    omegas.push_back(x * x * scale);
  }
  return omegas;
}

}  // namespace eqhb
