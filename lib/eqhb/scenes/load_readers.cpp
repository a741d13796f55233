#include "eqhb/scenes/load_readers.h"

#include "eqhb/error.h"
#include "eqhb/scenes/dof_choice.h"
#include "eqhb/structures/beam.h"
#include "eqhb/structures/matrix_market.h"

namespace eqhb::scene_reading {

namespace {

// The DOF (from 0) a load names: `dof` by number from 1 or by name as
// [output] names DOFs ("w8", "thetay3", "x5"), or `node`, a beam's node
// (its deflection).
int loadDof(TableReader& f, const std::string& field, const std::string& source, const HbModel& model, int nodes) {
  if (f.has("dof") && f.raw("dof").is_string()) {
    int dof = -1;
    bounded(source, [&] { dof = resolveDof(model, f.raw("dof").as_string().str, field + ".dof"); });
    return dof;
  }
  const bool by_node = f.has("node");
  const int number = f.integer(by_node ? "node" : "dof");
  const int count = by_node ? nodes : model.structure.dofs();
  if (by_node && count == 0)
    f.fail(field + ".node", std::to_string(number), "this structure has no nodes (only beams have): use dof");
  if (number < 1 || number > count)
    f.fail(field + (by_node ? ".node" : ".dof"), std::to_string(number),
           std::string(by_node ? "no such node" : "no such DOF") + " (the structure has " + std::to_string(count) +
               ", numbered from 1)");
  return by_node ? beamTransverseDof(number) : number - 1;
}

// A load vector (Matrix Market, n x 1) scaled by cos and sin: one load a
// DOF where the vector is not zero, each as `load` but for its DOF.
void readLoadFile(TableReader& f, const std::string& field, const std::string& source, const HarmonicLoad& load,
                  HbModel* model) {
  const int dofs = model->structure.dofs();
  const std::string path = relativeToScene(source, f.text("file"));
  // Its length by the size line, before its entries are read.
  MatrixMarketSize declared;
  bounded(source + ": " + field + ".file", [&] { declared = readMatrixMarketSize(path); });
  const long length = declared.rows == 1 ? declared.cols : declared.rows;
  if (declared.rows != 1 && declared.cols != 1)
    f.fail(field + ".file", "\"" + path + "\"",
           "a load vector must be n x 1 or 1 x n, its size line says " + std::to_string(declared.rows) + " x " +
               std::to_string(declared.cols));
  if (length != dofs)
    f.fail(field + ".file", "\"" + path + "\"",
           "has " + std::to_string(length) + " entries, the structure has " + std::to_string(dofs) + " DOFs");
  Eigen::VectorXd shape;
  bounded(source + ": " + field + ".file", [&] { shape = readMatrixMarketVector(path); });
  const double c = f.number("cos", 1.0), s_ = f.number("sin", 0.0);
  f.requireKnownKeys();
  for (int i = 0; i < dofs; ++i) {
    if (shape[i] == 0.0) continue;
    HarmonicLoad entry = load;
    entry.dof = i;
    entry.cos_amplitude = c * shape[i];
    entry.sin_amplitude = s_ * shape[i];
    model->structure.loads.push_back(entry);
  }
}

}  // namespace

void readForcing(TableReader& top, const std::string& source, int nodes, HbModel* model) {
  if (!top.has("forcing")) return;
  const auto& loads = arrayOfTables(top, "forcing");
  for (size_t i = 0; i < loads.size(); ++i) {
    const std::string field = "forcing[" + std::to_string(i) + "]";
    TableReader f(loads[i], field, source);
    HarmonicLoad load;
    load.harmonic = f.integer("harmonic", 1);
    if (load.harmonic < 0) f.fail(field + ".harmonic", std::to_string(load.harmonic), "must be >= 0");
    const int given = int(f.has("dof")) + int(f.has("node")) + int(f.has("file"));
    if (given != 1)
      f.fail(field, "(" + std::to_string(given) + " of dof, node, file)", "give exactly one of dof, node or file");
    if (f.has("file")) {
      readLoadFile(f, field, source, load, model);
      continue;
    }
    load.dof = loadDof(f, field, source, *model, nodes);
    load.cos_amplitude = f.number("cos", 0.0);
    load.sin_amplitude = f.number("sin", 0.0);
    f.requireKnownKeys();
    model->structure.loads.push_back(load);
  }
}

void readPreload(TableReader& top, const std::string& source, int nodes, HbModel* model,
                 std::vector<HarmonicLoad>* preload) {
  if (!top.has("preload")) return;
  const auto& loads = arrayOfTables(top, "preload");
  for (size_t i = 0; i < loads.size(); ++i) {
    const std::string field = "preload[" + std::to_string(i) + "]";
    TableReader f(loads[i], field, source);
    if (f.has("dof") == f.has("node")) f.fail(field, "(dof and node)", "give exactly one of dof or node");
    HarmonicLoad load;
    load.harmonic = 0;
    load.dof = loadDof(f, field, source, *model, nodes);
    load.cos_amplitude = f.number("force");
    f.requireKnownKeys();
    if (!model->basis.contains(0))
      f.fail(field, "(harmonic_balance.set = \"odd\")", "a static load needs the constant term: set = \"all\"");
    preload->push_back(load);
    model->structure.loads.push_back(load);
  }
}

}  // namespace eqhb::scene_reading
