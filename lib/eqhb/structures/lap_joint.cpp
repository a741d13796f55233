#include "eqhb/structures/lap_joint.h"

#include <array>
#include <string>

#include "eqhb/error.h"
#include "eqhb/structures/frame.h"

namespace eqhb {

namespace {

void checkParameters(const LapJointParameters& p) {
  if (p.pairs < 2)
    throwInputError("structure.pairs", std::to_string(p.pairs), "must be >= 2 (a pair at each end of the overlap)");
  if (p.elements < 1) throwInputError("structure.elements", std::to_string(p.elements), "must be >= 1");
  requirePositive("structure.L", p.length);
  requirePositive("structure.overlap", p.overlap);
  if (!(p.overlap < p.length))
    throwInputError("structure.overlap", formatNumber(p.overlap),
                    "must be shorter than each beam (structure.L = " + formatNumber(p.length) + ")");
  requirePositive("structure.h", p.thickness);
  requirePositive("structure.b", p.width);
  requirePositive("structure.E", p.youngs_modulus);
  requirePositive("structure.rho", p.density);
}

// One beam's elements: `outside` elements of length `outer` between its
// clamp and the overlap, then pairs − 1 of length `inner`. Node j of the
// beam is numbered from its clamp (1..beam_nodes; the clamp is node 0).
void assembleBeam(const FrameSection& section, int beam, int beam_nodes, int outside, double outer, double inner,
                  std::vector<Eigen::Triplet<double>>* k, std::vector<Eigen::Triplet<double>>* m) {
  for (int e = 0; e < beam_nodes; ++e) {
    // Element e joins node e and e + 1 counted from the clamp. The lower
    // beam is numbered from its clamp at the right: its element runs from
    // node e + 1 (left) to node e (right), so the frame's x points right for both.
    const int left = beam == 0 ? e : e + 1, right = beam == 0 ? e + 1 : e;
    std::array<int, 6> dofs;
    for (int c = 0; c < 3; ++c) {
      dofs[c] = left == 0 ? -1 : lapJointDof(beam_nodes, beam, left, c);
      dofs[3 + c] = right == 0 ? -1 : lapJointDof(beam_nodes, beam, right, c);
    }
    addFrameElement(section, e < outside ? outer : inner, dofs, k, m);
  }
}

}  // namespace

LapJoint lapJoint(const LapJointParameters& p) {
  checkParameters(p);
  FrameSection section;
  section.youngs_modulus = p.youngs_modulus;
  section.area = p.width * p.thickness;
  section.second_moment = p.width * p.thickness * p.thickness * p.thickness / 12.0;
  section.mass_per_length = p.density * section.area;
  LapJoint joint;
  joint.beam_nodes = p.elements + p.pairs - 1;
  const int n = 6 * joint.beam_nodes;
  const double outer = (p.length - p.overlap) / p.elements, inner = p.overlap / (p.pairs - 1);
  std::vector<Eigen::Triplet<double>> k, m;
  for (int beam = 0; beam < 2; ++beam) assembleBeam(section, beam, joint.beam_nodes, p.elements, outer, inner, &k, &m);
  const StructureMatrices frame = fromElementTriplets(n, m, k);

  // x = T x̃: u = u_s − (h/2) θ on the upper beam's overlap nodes, u = u_s + (h/2) θ on the lower's.
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, 1.0);
  std::vector<std::vector<long long>> upper, lower;  // node table rows, 1-based DOFs
  for (int pair = 1; pair <= p.pairs; ++pair) {
    // Pair 1 is at the lower beam's free end, pair `pairs` at the upper's.
    const int upper_node = p.elements + pair - 1, lower_node = p.elements + p.pairs - pair;
    const int nodes[2] = {upper_node, lower_node};
    for (int beam = 0; beam < 2; ++beam) {
      const int u = lapJointDof(joint.beam_nodes, beam, nodes[beam], 0);
      const int theta = lapJointDof(joint.beam_nodes, beam, nodes[beam], 2);
      t.emplace_back(u, theta, (beam == 0 ? -0.5 : 0.5) * p.thickness);
      (beam == 0 ? upper : lower).push_back({u + 1, lapJointDof(joint.beam_nodes, beam, nodes[beam], 1) + 1});
    }
  }
  Eigen::SparseMatrix<double> transform(n, n);
  transform.setFromTriplets(t.begin(), t.end());
  const Eigen::SparseMatrix<double> transposed = transform.transpose();
  joint.matrices.mass = transposed * frame.mass * transform;
  joint.matrices.stiffness = transposed * frame.stiffness * transform;
  joint.matrices.damping.resize(n, n);
  upper.insert(upper.end(), lower.begin(), lower.end());
  joint.surfaces = makeNodeTable(upper, n, "structure");
  return joint;
}

}  // namespace eqhb
