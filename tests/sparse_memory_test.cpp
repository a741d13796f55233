// The sparse path never forms a dense (n nb)² matrix: a full system of
// 20,050 unknowns (a dense Jacobian would take 3.2 GB) is built and solved
// while global operator new records the largest single allocation (standard
// containers) and getrusage the peak resident memory (Eigen's dense storage
// comes from malloc, which operator new does not see).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>

#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/structures/chain_pattern.h"
#include "observed_new.h"
#include "test_support.h"

namespace {
std::atomic<std::size_t> largest{0};
}

void observeAllocation(std::size_t size) {
  std::size_t seen = largest.load();
  while (size > seen && !largest.compare_exchange_weak(seen, size)) {
  }
}

namespace eqhb {
namespace {

double peakResidentMib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // KiB on Linux
}

// A chain of n unit masses and springs with friction on five DOFs.
HbModel longChain(int n) {
  const SparseMatrix k = chainPattern(n);
  SparseMatrix m(n, n);
  m.setIdentity();
  HbModel model;
  model.structure = LinearStructure::fromMassStiffnessDamping(m, k, SparseMatrix(0.05 * k));
  model.structure.loads.push_back({0, 1, 1.0, 0.0});
  for (int c = 1; c <= 5; ++c)
    model.laws.push_back({{c * n / 6}, std::make_shared<Coulomb1D>(0.05, CoulombForm::kMinMax)});
  model.basis = HarmonicSet(HarmonicKind::kOdd, 5);
  model.samples = 64;
  model.omega = 0.3;
  return model;
}

TEST(SparseMemory, FullSolveOfTwentyThousandUnknownsAllocatesNoDenseMatrix) {
  const HbModel model = longChain(2000);
  const double resident_before = peakResidentMib();
  largest = 0;
  FullSystem system(model);
  const std::size_t n = static_cast<std::size_t>(system.size());
  ASSERT_EQ(n, 20050u);
  SolverOptions options;  // automatic choice: sparse at this size
  const SolverResult result =
      makeSolver("dogleg-newton")->solve(system, Eigen::VectorXd::Zero(system.size()), options);
  ASSERT_TRUE(result.converged()) << result.summary();
  EXPECT_NE(result.native_message.find("sparse LU"), std::string::npos) << result.native_message;
  // The largest block: vectors, the pattern, UMFPACK's factors; a dense
  // matrix would be n² · 8 bytes = 3.2 GB.
  EXPECT_LT(largest.load(), 200 * n * sizeof(double)) << "largest allocation " << largest.load();
  EXPECT_LT(peakResidentMib() - resident_before, 300.0) << "peak resident memory grew beyond 300 MiB";
}

}  // namespace
}  // namespace eqhb
