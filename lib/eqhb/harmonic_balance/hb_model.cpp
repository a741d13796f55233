#include "eqhb/harmonic_balance/hb_model.h"

#include <algorithm>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/system_memory.h"
#include "eqhb/size_limits.h"

namespace eqhb {

int samplesForHarmonics(const HbModel& model, int harmonics) {
  const HarmonicSet basis(model.basis.kind(), harmonics);
  if (basis.highest() <= model.basis.highest() && model.samples >= basis.minimumSamples()) return model.samples;
  const double ratio = static_cast<double>(basis.highest()) / std::max(1, model.basis.highest());
  const double scaled = std::min(std::ceil(model.samples * ratio), 1e9);
  return std::max({basis.minimumSamples(), model.samples, static_cast<int>(scaled)});
}

void HbModel::validate() const {
  if (!(omega > 0.0) || !std::isfinite(omega))
    throwInputError("omega", formatNumber(omega), "must be finite and > 0");
  if (samples > kMaxSamples)
    throwInputError("samples", std::to_string(samples), "must be <= " + std::to_string(kMaxSamples));
  if (samples < basis.minimumSamples())
    throwInputError("samples", std::to_string(samples),
                    "must be >= 2 k_max + 1 = " + std::to_string(basis.minimumSamples()) +
                        " for the highest harmonic k_max = " + std::to_string(basis.highest()));
  // Bounded by the memory every system of the model needs, from the sizes
  // alone: before the structure's checks, which factorise M.
  checkBytes("harmonics", std::to_string(basis.count()), "the model " + describeSizes(*this), modelBytes(*this));
  structure.validate();
  for (size_t i = 0; i < structure.loads.size(); ++i) {
    const auto& load = structure.loads[i];
    const std::string field = "forcing[" + std::to_string(i) + "].harmonic";
    if (!basis.contains(load.harmonic))
      throwInputError(field, std::to_string(load.harmonic),
                      "not in the " + HarmonicSet::kindName(basis.kind()) +
                          " harmonic set with H = " + std::to_string(basis.count()) +
                          " (highest " + std::to_string(basis.highest()) + ")");
    if (load.harmonic == 0 && load.sin_amplitude != 0.0)
      throwInputError("forcing[" + std::to_string(i) + "].sin", formatNumber(load.sin_amplitude),
                      "a static load (harmonic 0) has no sine part");
  }
  for (size_t l = 0; l < laws.size(); ++l) {
    const auto& attached = laws[l];
    const std::string field = "law[" + std::to_string(l) + "]";
    if (!attached.law) throwInputError(field, "(null)", "no law given");
    const int d = attached.law->dimension();
    if (attached.attachment.dimension() != d)
      throwInputError(field + ".dofs", std::to_string(attached.attachment.dimension()) + " DOF(s)",
                      "a " + attached.law->type() + " law acts on exactly " +
                          std::to_string(d) + " DOF(s)");
    if (attached.law->needsConstantTerm() && !basis.contains(0))
      throwInputError("harmonic_balance.set", "\"" + HarmonicSet::kindName(basis.kind()) + "\"",
                      field + " (" + attached.law->type() +
                          ") needs the constant term (harmonic 0): its force is one-sided, so "
                          "its mean is not zero; use set = \"all\"");
    attached.attachment.validate(structure.dofs(), field + ".dofs");
  }
}

int HbModel::lawComponents() const {
  int count = 0;
  for (const auto& attached : laws) count += attached.law->dimension();
  return count;
}

void HbModel::checkSolutionSize(const Eigen::VectorXd& full, int dofs) const {
  if (dofs < 0) dofs = structure.dofs();
  const Eigen::Index size = static_cast<Eigen::Index>(basis.size()) * (dofs + lawComponents());
  if (full.size() != size)
    throwInputError("solution", std::to_string(full.size()) + " coefficients",
                    "must have " + std::to_string(size) + " ([x; lambda] of the full system)");
}

int HbModel::componentIndex(int l, int a) const {
  int index = 0;
  for (int i = 0; i < l; ++i) index += laws[i].law->dimension();
  return index + a;
}

}  // namespace eqhb
