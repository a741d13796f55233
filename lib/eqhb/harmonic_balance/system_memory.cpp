#include "eqhb/harmonic_balance/system_memory.h"

#include <algorithm>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/size_limits.h"

namespace eqhb {

namespace {
// Copies of a system Jacobian a solver may hold at once (the Jacobian, its
// factorisation, the previous one kept by the trust-region step).
constexpr double kJacobianCopies = 3.0;

double structureEntries(const LinearStructure& s) {
  return static_cast<double>(s.mass.nonZeros()) + s.damping.nonZeros() + s.stiffness.nonZeros();
}

// Entries of the union of the patterns of M, C and K (LinearStructure::
// pattern), counted column by column without building it.
double patternEntries(const LinearStructure& s) {
  double entries = 0.0;
  std::vector<int> rows;
  for (int j = 0; j < s.mass.outerSize(); ++j) {
    rows.clear();
    for (const SparseMatrix* m : {&s.mass, &s.damping, &s.stiffness})
      for (SparseMatrix::InnerIterator it(*m, j); it; ++it) rows.push_back(static_cast<int>(it.row()));
    std::sort(rows.begin(), rows.end());
    entries += static_cast<double>(std::unique(rows.begin(), rows.end()) - rows.begin());
  }
  return entries;
}
}  // namespace

ModelSizes modelSizes(const HbModel& model) {
  ModelSizes sizes;
  sizes.dofs = model.structure.dofs();
  sizes.structure_entries = structureEntries(model.structure);
  sizes.coefficients = model.basis.size();
  sizes.samples = model.samples;
  for (const auto& attached : model.laws) sizes.law_dimensions.push_back(attached.law ? attached.law->dimension() : 0);
  return sizes;
}

double modelBytes(const ModelSizes& sizes) {
  const double n = sizes.dofs, nb = sizes.coefficients, samples = sizes.samples;
  double bytes = sparseBytes(3.0 * n, sizes.structure_entries);
  double q = 0.0;
  for (int d : sizes.law_dimensions) q += d;
  bytes += 8.0 * 4.0 * (n + q) * nb;  // coefficients, residual, forcing, step
  for (const double d : sizes.law_dimensions)
    bytes += 8.0 * (2.0 * d * d * nb * nb + 4.0 * d * nb + 2.0 * d * samples);
  bytes += 8.0 * (2.0 * nb * nb + 2.0 * samples);  // Gram and velocity scratch, FFT buffers
  return bytes;
}

double modelBytes(const HbModel& model) { return modelBytes(modelSizes(model)); }

double condensedBytes(const HbModel& model, bool sparse_factors) {
  const double n = model.structure.dofs(), nb = model.basis.size(), q = model.lawComponents();
  const double pattern = sparse_factors ? patternEntries(model.structure) : 0.0;
  double factors = 0.0;
  for (int k : model.basis.harmonics()) {
    const double w = k == 0 ? 1.0 : 2.0;
    factors += sparse_factors ? sparseBytes(w * n, w * w * pattern)
                              : 2.0 * 8.0 * (w * n) * (w * n);  // A_k and its LU
  }
  const double receptance = 8.0 * q * q * nb * 2.0 + 8.0 * q * nb;
  const double unknowns = q * nb;
  return modelBytes(model) + factors + receptance + kJacobianCopies * 8.0 * unknowns * unknowns;
}

double fullBytes(const HbModel& model) {
  const double n = model.structure.dofs(), nb = model.basis.size(), q = model.lawComponents();
  const double pattern = patternEntries(model.structure);
  double entries = 0.0;
  for (int k : model.basis.harmonics()) {
    const double w = k == 0 ? 1.0 : 2.0;
    entries += w * w * pattern;
  }
  for (const auto& attached : model.laws) {
    const double d = attached.law ? attached.law->dimension() : 0.0;
    entries += d * nb + 2.0 * d * d * nb * nb;
  }
  // Set-up: two triplet lists (16 bytes an entry) besides the compressed pattern.
  return modelBytes(model) + 32.0 * entries + (1.0 + kJacobianCopies) * sparseBytes((n + q) * nb, entries);
}

std::string describeSizes(const HbModel& model) {
  const ModelSizes sizes = modelSizes(model);  // a law not given yet counts 0
  int q = 0;
  for (int d : sizes.law_dimensions) q += d;
  return "(" + formatNumber(sizes.dofs) + " DOFs, " + std::to_string(q) + " law components, " +
         formatNumber(sizes.coefficients) + " coefficients and " + formatNumber(sizes.samples) +
         " samples per channel)";
}

}  // namespace eqhb
