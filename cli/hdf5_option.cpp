#include "hdf5_option.h"

#include <stdexcept>

#ifdef EQHB_WITH_HDF5
#include "eqhb/output/backbone_hdf5.h"
#include "eqhb/output/results_hdf5.h"
#endif

namespace eqhb::cli {

void addHdf5Option(CLI::App* command, std::string& path, const std::string& what) {
  command->add_option("--hdf5", path, "Write " + what + " as HDF5 (h5py-readable; the JSON's numbers as arrays)");
}

#ifdef EQHB_WITH_HDF5
void writeSweepHdf5File(const std::string& path, const app::SweepResult& r) { output::writeSweepHdf5(path, r); }
void writeStudyHdf5File(const std::string& path, const app::StudyRun& run) { output::writeStudyHdf5(path, run); }
void writeBackboneHdf5File(const std::string& path, const app::ModesRun& run) { output::writeBackboneHdf5(path, run); }
#else
namespace {
[[noreturn]] void noHdf5(const std::string& path) {
  throw std::runtime_error("--hdf5 " + path + ": this eqhb was built without HDF5 (libhdf5-dev, EQHB_WITH_HDF5)");
}
}  // namespace
void writeSweepHdf5File(const std::string& path, const app::SweepResult&) { noHdf5(path); }
void writeStudyHdf5File(const std::string& path, const app::StudyRun&) { noHdf5(path); }
void writeBackboneHdf5File(const std::string& path, const app::ModesRun&) { noHdf5(path); }
#endif

}  // namespace eqhb::cli
