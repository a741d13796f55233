// libFuzzer target: a scene text through parsing, validation and the set-up
// of both harmonic-balance systems, with one residual evaluation each. Bad
// input must end in InputError (or the condensed system's singular-operator
// runtime_error); any other exception, a crash, a leak or undefined
// behaviour is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/system_memory.h"
#include "eqhb/scenes/scene.h"

namespace {

// Set-up of larger models is skipped: they are legitimate, only slow, and
// the size limits that refuse the huge ones are checked without building.
constexpr double kSetUpBytes = 64.0 * 1024 * 1024;

void setUp(const eqhb::HbModel& model, bool condensed) {
  const bool sparse = model.structure.dofs() >= eqhb::kSparseCondensationFromDofs;
  if ((condensed ? eqhb::condensedBytes(model, sparse) : eqhb::fullBytes(model)) > kSetUpBytes) return;
  try {
    auto system = eqhb::makeHbSystem(model, condensed);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(system->size()), g(system->size());
    system->residual(z, g);
  } catch (const eqhb::InputError&) {
  } catch (const std::runtime_error&) {
    if (!condensed) throw;  // only condensation may fail on a singular A_k
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  eqhb::Scene scene;
  try {
    scene = eqhb::parseScene(text, "fuzz.toml");
  } catch (const eqhb::InputError&) {
    return 0;
  }
  setUp(scene.model, true);
  setUp(scene.model, false);
  return 0;
}
