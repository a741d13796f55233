#include "eqhb/scenes/structure_readers.h"

#include <algorithm>
#include <iterator>
#include <utility>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/size_limits.h"
#include "eqhb/structures/chain_pattern.h"
#include "eqhb/structures/frame.h"
#include "eqhb/structures/lap_joint.h"
#include "eqhb/structures/market_structure_sizes.h"
#include "eqhb/structures/matrix_market.h"
#include "eqhb/structures/space_frame.h"
#include "eqhb/structures/structure_matrices.h"
#include "eqhb/scenes/dof_choice.h"

namespace eqhb::scene_reading {

namespace {

// C from the damping keys shared by the matrix-market and beam types:
// rayleigh = [alpha, beta] or modal_damping = zeta (none: C = 0).
void readDampingModel(TableReader& s, StructureMatrices& matrices) {
  const bool rayleigh = s.has("rayleigh"), modal = s.has("modal_damping");
  if (rayleigh && modal)
    s.fail("structure.rayleigh", "(and modal_damping)", "give one damping model, not both");
  if (rayleigh) {
    const toml::value& v = s.raw("rayleigh");
    if (!v.is_array() || v.as_array().size() != 2)
      s.fail("structure.rayleigh", describe(v), "must be [alpha, beta] (C = alpha M + beta K)");
    double ab[2];
    for (int i = 0; i < 2; ++i) {
      ab[i] = s.numberIn(v.as_array()[i], "structure.rayleigh[" + std::to_string(i) + "]", "entries must be numbers");
      if (ab[i] < 0.0)
        s.fail("structure.rayleigh", describe(v), "alpha and beta must be finite and >= 0");
    }
    matrices.damping = rayleighDamping(matrices, ab[0], ab[1]);
  } else if (modal) {
    const double zeta = s.number("modal_damping");
    if (zeta < 0.0) s.fail("structure.modal_damping", formatNumber(zeta), "damping ratio must be >= 0");
    matrices.damping = modalDamping(matrices, zeta, "structure.modal_damping");
  } else if (matrices.damping.rows() == 0) {
    matrices.damping.resize(matrices.mass.rows(), matrices.mass.cols());
  }
}

// Refuses a model too large for memory before its structure of `dofs` DOFs
// and `entries` stored entries of M, C and K is built or read (`extra`:
// what building it needs besides). The laws are not known yet; they are
// counted again, with everything else, when the model is validated.
void checkModelBeforeBuilding(const std::string& source, ModelSizes settings, const std::string& field,
                              const std::string& value, double dofs, double entries, double extra = 0.0) {
  // Without a structure too large already: the harmonics are to blame, and
  // HbModel::validate names them (with the laws) before M is factorised.
  if (modelBytes(settings) > kMaxModelBytes) return;
  settings.dofs = dofs;
  settings.structure_entries = entries;
  bounded(source, [&] {
    checkBytes(field, value,
               "the model (" + formatNumber(dofs) + " DOFs, " + formatNumber(settings.coefficients) +
                   " coefficients and " + formatNumber(settings.samples) + " samples per channel, before its laws)",
               modelBytes(settings) + extra);
  });
}

// `node_table`: rows of DOFs inline ([[1, 2, 3], [4, 5, 6]]: node i is row i)
// or a file of lines `node dof [dof ...]` (structures/node_table.h).
NodeTable readNodeTableKey(TableReader& s, const std::string& source, int dofs) {
  const toml::value& v = s.raw("node_table");
  NodeTable table;
  if (v.is_string()) {
    const std::string path = relativeToScene(source, s.text("node_table"));
    bounded(source, [&] { table = readNodeTable(path, dofs, "structure.node_table"); });
    return table;
  }
  if (!v.is_array() || v.as_array().empty())
    s.fail("structure.node_table", describe(v), "must be a file name or a non-empty array of DOF lists");
  std::vector<std::vector<long long>> rows;
  for (size_t i = 0; i < v.as_array().size(); ++i) {
    const toml::value& row = v.as_array()[i];
    const std::string field = "structure.node_table[" + std::to_string(i) + "]";
    if (!row.is_array()) s.fail(field, describe(row), "must be a list of DOF numbers");
    rows.emplace_back();
    for (const auto& e : row.as_array()) {
      if (!e.is_integer()) s.fail(field, describe(row), "DOF numbers must be integers");
      rows.back().push_back(e.as_integer());
    }
  }
  bounded(source, [&] { table = makeNodeTable(rows, dofs, "structure.node_table"); });
  return table;
}

// The structure types: each reads M, C, K (and nodes) from the [structure]
// table, `settings` being the coefficients and samples of the model the
// structure is for (memory is bounded before anything is built). A new type
// is one reader and one line of kStructureTypes.
using StructureReader = void (*)(TableReader& s, const std::string& source, const ModelSizes& settings, ReadStructure* read);

// n masses m fixed at DOF 1's end and free after DOF n: M = m I, K = k T, C = d T.
void readChain(TableReader& s, const std::string& source, const ModelSizes& settings, ReadStructure* read) {
  const int n = s.integer("dofs", 2);
  if (n < 1) s.fail("structure.dofs", std::to_string(n), "must be >= 1");
  // Sparse: n entries in M, 3n − 2 in C and K (a dense M, C, K would take 24 n²
  // bytes; the dense path is bounded where it is chosen).
  bounded(source, [&] {
    checkBytes("structure.dofs", std::to_string(n), "a chain's sparse M, C and K",
               sparseBytes(n, n) + 2.0 * sparseBytes(n, 3.0 * n));
  });
  checkModelBeforeBuilding(source, settings, "structure.dofs", std::to_string(n), n, 7.0 * n);
  const double m = s.number("m"), k = s.number("k"), d = s.number("d");
  if (!(m > 0.0)) s.fail("structure.m", formatNumber(m), "mass must be > 0");
  if (k < 0.0) s.fail("structure.k", formatNumber(k), "stiffness must be >= 0");
  if (d < 0.0) s.fail("structure.d", formatNumber(d), "damping must be >= 0");
  const SparseMatrix t = chainPattern(n);
  SparseMatrix identity(n, n);
  identity.setIdentity();
  read->structure = LinearStructure::fromMassStiffnessDamping(SparseMatrix(m * identity), SparseMatrix(k * t),
                                                              SparseMatrix(d * t));
}

// Small M, C, K given inline.
void readInlineMatrices(TableReader& s, const std::string& source, const ModelSizes& settings, ReadStructure* read) {
  (void)settings;
  StructureMatrices matrices;
  // K, C, M in this order: a scene with several bad matrices is refused
  // naming the stiffness first, then the damping.
  matrices.stiffness = s.matrix("stiffness").sparseView(1.0, 0.0);
  matrices.damping = s.matrix("damping").sparseView(1.0, 0.0);
  matrices.mass = s.matrix("mass").sparseView(1.0, 0.0);
  read->structure = toLinearStructure(matrices);
  // Named like every other field: the file, then the key.
  MatrixNames names;
  names.mass = source + ": structure.mass";
  names.damping = source + ": structure.damping";
  names.stiffness = source + ": structure.stiffness";
  checkStructureMatrices(matrices, 1e-12, names);
}

// M, K (and C, or a damping model) from Matrix Market files.
void readMarketStructure(TableReader& s, const std::string& source, const ModelSizes& settings, ReadStructure* read) {
  const double tolerance = s.number("symmetry_tolerance", 1e-8);
  if (!(tolerance >= 0.0)) s.fail("structure.symmetry_tolerance", formatNumber(tolerance), "must be >= 0");
  MatrixNames names;
  names.mass = relativeToScene(source, s.text("mass"));
  names.stiffness = relativeToScene(source, s.text("stiffness"));
  const bool damping_file = s.has("damping");
  if (damping_file && (s.has("rayleigh") || s.has("modal_damping")))
    s.fail("structure.damping", describe(s.raw("damping")),
           "give one damping model: a damping file, rayleigh or modal_damping");
  if (damping_file) names.damping = relativeToScene(source, s.text("damping"));
  // The size lines first: M, K (and C) square and of one size, and the
  // model within memory, before any entry is read.
  MarketStructureSizes declared;
  bounded(source, [&] {
    declared = checkMarketStructureSizes({"structure.mass", names.mass}, {"structure.stiffness", names.stiffness},
                                         {"structure.damping", damping_file ? names.damping : std::string()});
  });
  const double n = static_cast<double>(declared.dofs);
  if (s.has("modal_damping"))
    checkModalDampingSize(static_cast<int>(declared.dofs), s.number("modal_damping"), "structure.modal_damping");
  // C from a model: rayleigh has at most the entries of M and K, modal is dense.
  const double modelled_damping =
      damping_file ? 0.0 : s.has("modal_damping") ? n * n : s.has("rayleigh") ? declared.stored_entries : 0.0;
  checkModelBeforeBuilding(source, settings, "structure.mass", "\"" + names.mass + "\"", n,
                           declared.stored_entries + modelled_damping, declared.reading_bytes);
  StructureMatrices matrices;
  bounded(source + ": structure.mass", [&] { matrices.mass = readMatrixMarket(names.mass); });
  bounded(source + ": structure.stiffness", [&] { matrices.stiffness = readMatrixMarket(names.stiffness); });
  if (damping_file)
    bounded(source + ": structure.damping", [&] { matrices.damping = readMatrixMarket(names.damping); });
  // Sizes and symmetry of M and K first: the damping models build on them.
  if (!damping_file) names.damping = "structure.damping (from M and K)";
  {
    StructureMatrices mk = matrices;
    mk.damping = matrices.mass;
    checkStructureMatrices(mk, tolerance, names);
  }
  readDampingModel(s, matrices);
  checkStructureMatrices(matrices, tolerance, names);
  read->structure = toLinearStructure(matrices);
}

// Bounds an element assembly before it is built: `dofs` unknowns, `entries`
// in each of M, C and K, and the triplets M and K are summed from; named by
// `field` = `value`.
void boundAssembly(const std::string& source, const ModelSizes& settings, const std::string& field,
                   const std::string& value, const std::string& what, double dofs, double entries) {
  bounded(source, [&] { checkBytes(field, value, what, 3.0 * sparseBytes(dofs, entries) + 2.0 * 16.0 * entries); });
  checkModelBeforeBuilding(source, settings, field, value, dofs, 3.0 * entries);
}

// A beam's or frame's `elements`, its M, C and K bounded before they are
// built: `dofs_per_node` DOFs a node, `entries_per_element` entries an
// element in M and K (and C).
int readElementCount(TableReader& s, const std::string& source, const ModelSizes& settings, const std::string& what,
                     double dofs_per_node, double entries_per_element) {
  const int elements = s.integer("elements");
  const double e = std::max(elements, 0);
  boundAssembly(source, settings, "structure.elements", std::to_string(elements), what, dofs_per_node * e,
                entries_per_element * e);
  return elements;
}

// An element assembly's structure: M and K from `assemble` (run bounded, so
// that a refusal names the scene), C from the damping keys.
template <class Assemble>
void readAssembled(TableReader& s, const std::string& source, ReadStructure* read, const Assemble& assemble) {
  StructureMatrices matrices;
  bounded(source, [&] { matrices = assemble(); });
  readDampingModel(s, matrices);
  read->structure = toLinearStructure(matrices);
}

// Node i → its first three DOFs (a frame node's DOFs that an element between
// two nodes reads), for nodes 1..nodes.
template <class DofOf>
std::vector<std::vector<int>> firstThreeDofs(int nodes, const DofOf& dof_of) {
  std::vector<std::vector<int>> table;
  for (int node = 1; node <= nodes; ++node) table.push_back({dof_of(node, 0), dof_of(node, 1), dof_of(node, 2)});
  return table;
}

// A cantilever Euler–Bernoulli beam (structures/beam.h), with a damping model.
void readBeam(TableReader& s, const std::string& source, const ModelSizes& settings, ReadStructure* read) {
  BeamParameters beam;
  beam.elements = readElementCount(s, source, settings, "a beam's sparse M, C and K", 2.0, 16.0);
  beam.youngs_modulus = s.number("E");
  beam.second_moment = s.number("I");
  beam.mass_per_length = s.number("rhoA");
  beam.length = s.number("L");
  StructureMatrices matrices = cantileverBeam(beam);
  readDampingModel(s, matrices);
  read->structure = toLinearStructure(matrices);
  read->nodes = beam.elements;
  read->dof_names = nodeDofNames(read->structure.dofs(), beam.elements, {"w", "theta"},
                                 [](int node, int c) { return beamTransverseDof(node) + c; });
}

// A cantilever plane frame (structures/frame.h): node i → its DOFs [u, w, θ].
void readFrame(TableReader& s, const std::string& source, const ModelSizes& settings, ReadStructure* read) {
  FrameParameters frame;
  frame.elements = readElementCount(s, source, settings, "a frame's sparse M, C and K", 3.0, 20.0);
  frame.section.youngs_modulus = s.number("E");
  frame.section.area = s.number("A");
  frame.section.second_moment = s.number("I");
  frame.section.mass_per_length = s.number("rhoA");
  frame.length = s.number("L");
  readAssembled(s, source, read, [&] { return cantileverFrame(frame); });
  read->node_table = firstThreeDofs(frame.elements, frameDof);
  read->dof_names = nodeDofNames(read->structure.dofs(), frame.elements, {"u", "w", "theta"}, frameDof);
}

// A cantilever space frame (structures/space_frame.h): node i is the point
// on its axis, so an element's directions are directions in space over its
// translations [u, v, w]; the rotations are reached by DOF name or number.
void readSpaceFrame(TableReader& s, const std::string& source, const ModelSizes& settings, ReadStructure* read) {
  SpaceFrameParameters frame;
  frame.elements = readElementCount(s, source, settings, "a space frame's sparse M, C and K", 6.0, 40.0);
  SpaceFrameSection& section = frame.section;
  section.youngs_modulus = s.number("E");
  section.shear_modulus = s.number("G");
  section.density = s.number("rho");
  section.area = s.number("A");
  section.second_moment_y = s.number("Iy");
  section.second_moment_z = s.number("Iz");
  section.torsion_constant = s.number("J");
  frame.length = s.number("L");
  readAssembled(s, source, read, [&] { return cantileverSpaceFrame(frame); });
  read->node_table = firstThreeDofs(frame.elements, spaceFrameDof);
  read->dof_names = nodeDofNames(read->structure.dofs(), frame.elements,
                                 {"u", "v", "w", "thetax", "thetay", "thetaz"}, spaceFrameDof);
}

// Two beams over a lap joint (structures/lap_joint.h): its nodes are the
// facing surfaces' points, [u_s, w] each. Its DOFs are named as a frame's by
// the beams' nodes, the upper beam's 1..n and the lower's n + 1..2n from
// its clamp (u, w, theta), the overlap nodes' axial DOF "us" (the surface's
// slide u ± (h/2) θ, not the axis's u).
void readLapJoint(TableReader& s, const std::string& source, const ModelSizes& settings, ReadStructure* read) {
  LapJointParameters p;
  p.pairs = s.integer("pairs");
  p.elements = s.integer("elements");
  const double dofs = 6.0 * (std::max(p.pairs, 0) + std::max(p.elements, 0));
  boundAssembly(source, settings, "structure.pairs", std::to_string(p.pairs), "a lap joint's sparse M, C and K",
                dofs, 12.0 * dofs);
  p.length = s.number("L");
  p.overlap = s.number("overlap");
  p.thickness = s.number("h");
  p.width = s.number("b");
  p.youngs_modulus = s.number("E");
  p.density = s.number("rho");
  LapJoint joint;
  readAssembled(s, source, read, [&] {
    joint = lapJoint(p);
    return std::move(joint.matrices);
  });
  read->node_table = joint.surfaces;
  read->dof_names = nodeDofNames(read->structure.dofs(), 2 * joint.beam_nodes, {"u", "w", "theta"}, frameDof);
  for (const auto& surface : joint.surfaces) {
    const int slide = surface[0];
    read->dof_names[slide] = "us" + std::to_string(slide / 3 + 1);
  }
}

struct StructureType {
  const char* name;
  StructureReader read;
  bool takes_node_table;  // beams, frames and lap joints have nodes of their own
};
constexpr StructureType kStructureTypes[] = {{"chain", readChain, true},
                                             {"matrices", readInlineMatrices, true},
                                             {"matrix-market", readMarketStructure, true},
                                             {"beam", readBeam, false},
                                             {"frame", readFrame, false},
                                             {"space-frame", readSpaceFrame, false},
                                             {"lap-joint", readLapJoint, false}};

// "\"a\", \"b\" or \"c\"": the registered type names, for the message of an unknown one.
std::string structureTypeNames() {
  std::string out;
  const size_t n = std::size(kStructureTypes);
  for (size_t i = 0; i < n; ++i)
    out += (i == 0 ? "" : i + 1 == n ? " or " : ", ") + std::string("\"") + kStructureTypes[i].name + "\"";
  return out;
}

}  // namespace

ReadStructure readStructure(TableReader& top, const std::string& source, const ModelSizes& settings) {
  TableReader s(top.raw("structure"), "structure", source);
  const std::string type = s.text("type");
  ReadStructure read;
  const auto* found = std::find_if(std::begin(kStructureTypes), std::end(kStructureTypes),
                                   [&](const StructureType& t) { return type == t.name; });
  if (found == std::end(kStructureTypes))
    s.fail("structure.type", "\"" + type + "\"", "must be " + structureTypeNames());
  found->read(s, source, settings, &read);
  if (found->takes_node_table && s.has("node_table"))
    read.node_table = readNodeTableKey(s, source, read.structure.dofs());
  s.requireKnownKeys();
  return read;
}

}  // namespace eqhb::scene_reading
