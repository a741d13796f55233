// The hot path allocates nothing: residual and weak-Jacobian evaluations of
// every law, on both systems, after construction. Global operator new is
// replaced in this test binary to count heap allocations.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/laws/stribeck.h"
#include "test_support.h"

namespace {
std::atomic<long> allocations{0};
}

void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace eqhb {
namespace {

TEST(Allocation, ResidualAndJacobianAllocateNothing) {
  const std::vector<std::pair<std::vector<int>, std::shared_ptr<Law>>> laws = {
      {{1}, std::make_shared<Coulomb1D>(7.2, CoulombForm::kMinMax)},
      {{0, 1}, std::make_shared<Coulomb2D>(8.0, Coulomb2DForm::kMax)},
      {{1}, std::make_shared<Signorini>(2.0, SignoriniForm::kFischerBurmeister)},
      {{1}, std::make_shared<Stribeck>(1.0, 1.5, 0.5)},
      {{1}, std::make_shared<CubicStiffness>(0.5)}};
  for (const auto& [dofs, law] : laws)
    for (bool condensed : {true, false}) {
      HbModel model = test::chainWithFriction(7.2, CoulombForm::kMinMax, 10, 0.4, 512, HarmonicKind::kAll);
      model.laws = {{dofs, law}};
      const long at_start = allocations.load();
      auto system = makeHbSystem(model, condensed);
      ASSERT_GT(allocations.load(), at_start) << "the counter must see the construction's buffers";
      const Eigen::VectorXd z = Eigen::VectorXd::Constant(system->size(), 0.3);
      Eigen::VectorXd g(system->size());
      Eigen::MatrixXd j(system->size(), system->size());
      system->residualAndJacobian(z, g, j);  // warm-up
      const long before = allocations.load();
      for (int i = 0; i < 3; ++i) {
        system->residual(z, g);
        system->residualAndJacobian(z, g, j);
      }
      EXPECT_EQ(allocations.load() - before, 0) << law->type() << (condensed ? " condensed" : " full");
    }
}

}  // namespace
}  // namespace eqhb
