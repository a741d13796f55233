// libFuzzer target: a Matrix Market file's bytes through the reader (size
// line, memory bound, entries, as a matrix and as a load vector) and through
// a scene that uses it as the stiffness of a valid 2-DOF structure and as
// its load vector. Bad input must end in InputError; any other exception, a
// crash, a leak, undefined behaviour (the size line's products) or an
// allocation beyond -malloc_limit_mb is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "eqhb/error.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/structures/matrix_market.h"

namespace {

// Files the reader accepts but that are only slow to read are read no
// further than their size line (the bound itself is what is tested there).
constexpr double kReadBytes = 64.0 * 1024 * 1024;

// A 2-DOF scene with the fuzzed file "f.mtx" in place of one of its files.
std::string scene(const std::string& stiffness, const std::string& load) {
  return "name = \"fuzz\"\n[structure]\ntype = \"matrix-market\"\nmass = \"m.mtx\"\nstiffness = \"" + stiffness +
         "\"\nrayleigh = [0.02, 0.0]\n[[forcing]]\nfile = \"" + load +
         "\"\ncos = 1.0\n[[law]]\ntype = \"coulomb-1d\"\ndofs = [2]\nmuN = 0.5\n[harmonic_balance]\n"
         "harmonics = 3\nsamples = 64\nomega = 0.5\n";
}

// A folder of this process with a valid 2-DOF mass, stiffness and load
// beside the fuzzed file, removed at exit.
struct Folder {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("eqhb-mm-fuzz-" + std::to_string(::getpid()));
  Folder() {
    std::filesystem::create_directories(path);
    std::ofstream(path / "m.mtx") << "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n2 2 1\n";
    std::ofstream(path / "k.mtx") << "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 2\n2 1 -1\n2 2 1\n";
    std::ofstream(path / "f1.mtx") << "%%MatrixMarket matrix array real general\n2 1\n1\n0\n";
  }
  ~Folder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

const std::filesystem::path& folder() {
  static const Folder dir;
  return dir.path;
}

template <typename F>
void refusedOrRead(F&& f) {
  try {
    f();
  } catch (const eqhb::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = (folder() / "f.mtx").string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  // The stiffness, then the load of a 2-DOF scene: their size lines are
  // compared with the mass's before anything is read.
  const std::string source = (folder() / "fuzz.toml").string();
  refusedOrRead([&] { eqhb::parseScene(scene("f.mtx", "f1.mtx"), source); });
  refusedOrRead([&] { eqhb::parseScene(scene("k.mtx", "f.mtx"), source); });
  // The reader alone, as a matrix and as a vector.
  double bytes = 0.0;
  try {
    const eqhb::MatrixMarketSize declared = eqhb::readMatrixMarketSize(path);
    eqhb::checkMatrixMarketMemory(path, declared);
    bytes = declared.readBytes();
  } catch (const eqhb::InputError&) {
    return 0;
  }
  if (bytes > kReadBytes) return 0;
  refusedOrRead([&] { eqhb::readMatrixMarket(path); });
  refusedOrRead([&] { eqhb::readMatrixMarketVector(path); });
  return 0;
}
