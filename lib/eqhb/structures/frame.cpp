#include "eqhb/structures/frame.h"

#include <cmath>
#include <string>

#include "eqhb/error.h"
#include "eqhb/structures/beam.h"
#include "eqhb/structures/cantilever_assembly.h"

namespace eqhb {

void requirePositive(const char* field, double x) {
  if (!(x > 0.0) || !std::isfinite(x)) throwInputError(field, formatNumber(x), "must be finite and > 0");
}

void addFrameElement(const FrameSection& section, double length, const std::array<int, 6>& dofs,
                     std::vector<Eigen::Triplet<double>>* stiffness, std::vector<Eigen::Triplet<double>>* mass) {
  const double l = length;
  const double ea = section.youngs_modulus * section.area / l;
  const double ei = section.youngs_modulus * section.second_moment / (l * l * l);
  const double bar_mass = section.mass_per_length * l / 6.0;
  const double beam_mass = section.mass_per_length * l / 420.0;
  // Bending on (w1, θ1, w2, θ2): the Hermite blocks of beam.h.
  const HermiteBlocks blocks = hermiteBeamBlocks(l);
  auto add = [&](int i, int j, double k, double m) {
    if (i < 0 || j < 0) return;  // clamped
    if (k != 0.0) stiffness->emplace_back(i, j, k);
    if (m != 0.0) mass->emplace_back(i, j, m);
  };
  const int axial[2] = {dofs[0], dofs[3]};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) add(axial[a], axial[b], ea * (a == b ? 1.0 : -1.0), bar_mass * (a == b ? 2.0 : 1.0));
  const int bending[4] = {dofs[1], dofs[2], dofs[4], dofs[5]};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) add(bending[a], bending[b], ei * blocks.stiffness[a][b], beam_mass * blocks.mass[a][b]);
}

StructureMatrices cantileverFrame(const FrameParameters& frame) {
  if (frame.elements < 1) throwInputError("structure.elements", std::to_string(frame.elements), "must be >= 1");
  requirePositive("structure.E", frame.section.youngs_modulus);
  requirePositive("structure.A", frame.section.area);
  requirePositive("structure.I", frame.section.second_moment);
  requirePositive("structure.rhoA", frame.section.mass_per_length);
  requirePositive("structure.L", frame.length);
  const double l = frame.length / frame.elements;
  return assembleCantilever<3>(frame.elements, 20, [&](const auto& dofs, auto* k, auto* m) {
    addFrameElement(frame.section, l, dofs, k, m);
  });
}

std::vector<double> axialBarFrequencies(const FrameParameters& frame, int count) {
  std::vector<double> omegas;
  const double wave_speed = std::sqrt(frame.section.youngs_modulus * frame.section.area / frame.section.mass_per_length);
  for (int r = 1; r <= count; ++r) omegas.push_back((2 * r - 1) * M_PI / (2 * frame.length) * wave_speed);
  return omegas;
}

}  // namespace eqhb
