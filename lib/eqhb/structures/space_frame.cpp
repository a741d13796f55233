#include "eqhb/structures/space_frame.h"

#include <cmath>
#include <string>

#include "eqhb/error.h"
#include "eqhb/structures/beam.h"
#include "eqhb/structures/cantilever_assembly.h"
#include "eqhb/structures/frame.h"

namespace eqhb {

namespace {

enum Component { kU, kV, kW, kThetaX, kThetaY, kThetaZ };

double polarMoment(const SpaceFrameSection& s) { return s.second_moment_y + s.second_moment_z; }

}  // namespace

void addSpaceFrameElement(const SpaceFrameSection& section, double length, const std::array<int, 12>& dofs,
                          std::vector<Eigen::Triplet<double>>* stiffness, std::vector<Eigen::Triplet<double>>* mass) {
  const double l = length;
  auto add = [&](int i, int j, double k, double m) {
    if (i < 0 || j < 0) return;  // clamped
    if (k != 0.0) stiffness->emplace_back(i, j, k);
    if (m != 0.0) mass->emplace_back(i, j, m);
  };
  // Two-node linear members: the bar (u) and the shaft (θx).
  auto addLinear = [&](int component, double k, double m) {
    const int ends[2] = {dofs[component], dofs[6 + component]};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) add(ends[a], ends[b], k * (a == b ? 1.0 : -1.0), m * (a == b ? 2.0 : 1.0));
  };
  addLinear(kU, section.youngs_modulus * section.area / l, section.density * section.area * l / 6.0);
  addLinear(kThetaX, section.shear_modulus * section.torsion_constant / l, section.density * polarMoment(section) * l / 6.0);
  // Bending: the Hermite blocks on (deflection, slope) at both ends. In the
  // x–z plane the slope dw/dx is −θy, so θy's rows and columns change sign.
  const HermiteBlocks blocks = hermiteBeamBlocks(l);
  auto addBending = [&](int deflection, int rotation, double sign, double second_moment) {
    const int at[4] = {dofs[deflection], dofs[rotation], dofs[6 + deflection], dofs[6 + rotation]};
    const double signs[4] = {1.0, sign, 1.0, sign};
    const double ei = section.youngs_modulus * second_moment / (l * l * l);
    const double m = section.density * section.area * l / 420.0;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        add(at[a], at[b], signs[a] * signs[b] * ei * blocks.stiffness[a][b],
            signs[a] * signs[b] * m * blocks.mass[a][b]);
  };
  addBending(kV, kThetaZ, 1.0, section.second_moment_z);
  addBending(kW, kThetaY, -1.0, section.second_moment_y);
}

StructureMatrices cantileverSpaceFrame(const SpaceFrameParameters& frame) {
  if (frame.elements < 1) throwInputError("structure.elements", std::to_string(frame.elements), "must be >= 1");
  const SpaceFrameSection& s = frame.section;
  requirePositive("structure.E", s.youngs_modulus);
  requirePositive("structure.G", s.shear_modulus);
  requirePositive("structure.rho", s.density);
  requirePositive("structure.A", s.area);
  requirePositive("structure.Iy", s.second_moment_y);
  requirePositive("structure.Iz", s.second_moment_z);
  requirePositive("structure.J", s.torsion_constant);
  requirePositive("structure.L", frame.length);
  const double l = frame.length / frame.elements;
  return assembleCantilever<6>(frame.elements, 40, [&](const auto& dofs, auto* k, auto* m) {
    addSpaceFrameElement(frame.section, l, dofs, k, m);
  });
}

std::vector<double> torsionFrequencies(const SpaceFrameParameters& frame, int count) {
  const SpaceFrameSection& s = frame.section;
  const double wave_speed = std::sqrt(s.shear_modulus * s.torsion_constant / (s.density * polarMoment(s)));
  std::vector<double> omegas;
  for (int r = 1; r <= count; ++r) omegas.push_back((2 * r - 1) * M_PI / (2 * frame.length) * wave_speed);
  return omegas;
}

}  // namespace eqhb
