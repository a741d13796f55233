#include "eqhb/structures/market_structure_sizes.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/structures/matrix_market.h"

namespace eqhb {

namespace {
std::string shape(const MatrixMarketSize& size) {
  return std::to_string(size.rows) + " x " + std::to_string(size.cols);
}
}  // namespace

MarketStructureSizes checkMarketStructureSizes(const MarketFile& mass, const MarketFile& stiffness,
                                               const MarketFile& damping) {
  std::vector<std::pair<const MarketFile*, MatrixMarketSize>> files;
  for (const MarketFile* file : {&mass, &stiffness, &damping}) {
    if (file->path.empty()) continue;
    try {
      files.emplace_back(file, readMatrixMarketSize(file->path));
    } catch (const InputError& e) {
      throw InputError(file->field + ": " + e.what());
    }
  }
  // Shapes before memory: a mismatch is the clearer message.
  const long n = files.front().second.rows;
  for (const auto& [file, size] : files) {
    const std::string quoted = "\"" + file->path + "\"";
    if (size.rows != size.cols)
      throwInputError(file->field, quoted, "must be square, its size line says " + shape(size));
    if (size.rows != n)
      throwInputError(file->field, quoted,
                      "is " + shape(size) + ", the mass matrix is " + std::to_string(n) + " x " + std::to_string(n) +
                          " (sizes must agree; by the size lines, before reading)");
  }
  MarketStructureSizes sizes;
  sizes.dofs = n;
  for (const auto& [file, size] : files) {
    try {
      checkMatrixMarketMemory(file->path, size);
    } catch (const InputError& e) {
      throw InputError(file->field + ": " + e.what());
    }
    sizes.stored_entries += size.storedEntries();
    sizes.reading_bytes = std::max(sizes.reading_bytes, size.readBytes() - size.matrixBytes());
  }
  return sizes;
}

}  // namespace eqhb
