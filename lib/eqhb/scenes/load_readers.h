// A scene's [[forcing]] and [[preload]] tables: harmonic and static loads on
// a DOF (by number or name), a beam's node, or a load vector from a file.
#pragma once

#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/scenes/table_reader.h"

namespace eqhb::scene_reading {

// [[forcing]]: each table's loads added to model->structure.loads. `nodes`:
// the structure's beam nodes (0 where it has none).
void readForcing(TableReader& top, const std::string& source, int nodes, HbModel* model);
// [[preload]]: static loads (harmonic 0, so the set must hold the constant
// term), added to the model's loads and to `preload`.
void readPreload(TableReader& top, const std::string& source, int nodes, HbModel* model,
                 std::vector<HarmonicLoad>* preload);

}  // namespace eqhb::scene_reading
