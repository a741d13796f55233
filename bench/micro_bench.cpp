// Google Benchmark micro-benchmarks of the hot path, per law and vs H (and
// N): residual, residual + weak Jacobian (condensed system), condensation
// (setOmega: the per-harmonic linear solves) and one solver iteration
// (a dogleg solve limited to one iteration: Jacobian, QR, one step).
#include <benchmark/benchmark.h>

#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/laws/stribeck.h"
#include "eqhb/backends/registry.h"

namespace {

using namespace eqhb;

// The 2-DOF chain of the spec with one law of each kind (a planar law gets a
// planar pair of DOFs), H odd harmonics (all for contact), N samples.
HbModel model(int law, int harmonics, int samples) {
  HbModel m;
  Eigen::MatrixXd t(2, 2);
  t << 2, -1, -1, 1;
  const Eigen::MatrixXd k = law == 1 ? Eigen::MatrixXd::Identity(2, 2) : t;
  m.structure = LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd::Identity(2, 2), k, 0.02 * k);
  m.structure.loads.push_back({0, 1, 20.0, 0.0});
  HarmonicKind kind = HarmonicKind::kOdd;
  switch (law) {
    case 0: m.laws.push_back({{1}, std::make_shared<Coulomb1D>(7.2, CoulombForm::kMinMax)}); break;
    case 1:
      m.structure.loads.push_back({1, 3, 10.0, 0.0});
      m.laws.push_back({{0, 1}, std::make_shared<Coulomb2D>(8.0, Coulomb2DForm::kMax)});
      break;
    case 2:
      m.laws.push_back({{1}, std::make_shared<Signorini>(2.0, SignoriniForm::kMin)});
      kind = HarmonicKind::kAll;
      break;
    case 3: m.laws.push_back({{1}, std::make_shared<Stribeck>(1.0, 1.5, 0.5)}); break;
    default: m.laws.push_back({{1}, std::make_shared<CubicStiffness>(0.5)}); break;
  }
  m.basis = HarmonicSet(kind, harmonics);
  m.samples = samples;
  m.omega = 0.4;
  return m;
}

int samplesFor(int harmonics) {  // the smallest power of two >= 8 (2H + 1)
  int n = 64;
  while (n < 8 * (2 * harmonics + 1)) n *= 2;
  return n;
}

// The model of a (law, H) benchmark's arguments.
HbModel lawModel(const benchmark::State& state) {
  const int harmonics = static_cast<int>(state.range(1));
  return model(static_cast<int>(state.range(0)), harmonics, samplesFor(harmonics));
}

// Times residualAndJacobian at a fixed z.
void timeResidualAndJacobian(benchmark::State& state, CondensedSystem& system) {
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(system.size(), 0.3);
  Eigen::VectorXd g(system.size());
  Eigen::MatrixXd j(system.size(), system.size());
  for (auto _ : state) {
    system.residualAndJacobian(z, g, j);
    benchmark::DoNotOptimize(j.data());
  }
}

void Residual(benchmark::State& state) {
  const HbModel m = lawModel(state);
  CondensedSystem system(m);
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(system.size(), 0.3);
  Eigen::VectorXd g(system.size());
  for (auto _ : state) {
    system.residual(z, g);
    benchmark::DoNotOptimize(g.data());
  }
  state.SetLabel(m.laws[0].law->type());
}

void ResidualAndJacobian(benchmark::State& state) {
  const HbModel m = lawModel(state);
  CondensedSystem system(m);
  timeResidualAndJacobian(state, system);
  state.SetLabel(m.laws[0].law->type());
}

void ResidualVsSamples(benchmark::State& state) {
  CondensedSystem system(model(0, 10, static_cast<int>(state.range(0))));
  timeResidualAndJacobian(state, system);
  state.SetLabel("coulomb-1d, H = 10");
}

void Condensation(benchmark::State& state) {
  CondensedSystem system(model(0, static_cast<int>(state.range(0)), samplesFor(static_cast<int>(state.range(0)))));
  double omega = 0.4;
  for (auto _ : state) {
    omega = omega == 0.4 ? 0.41 : 0.4;
    system.setOmega(omega);
  }
  state.SetLabel("coulomb-1d");
}

void SolverIteration(benchmark::State& state) {
  CondensedSystem system(model(0, static_cast<int>(state.range(0)), samplesFor(static_cast<int>(state.range(0)))));
  auto solver = makeSolver("dogleg");
  SolverOptions options;
  options.max_iterations = 1;
  const Eigen::VectorXd z0 = Eigen::VectorXd::Zero(system.size());
  for (auto _ : state) {
    const SolverResult r = solver->solve(system, z0, options);
    benchmark::DoNotOptimize(r.final_norm);
  }
  state.SetLabel("coulomb-1d, dogleg");
}

void lawsAndHarmonics(benchmark::internal::Benchmark* b) {
  for (int law = 0; law < 5; ++law)
    for (int h : {5, 10, 20, 40, 80}) b->Args({law, h});
}

BENCHMARK(Residual)->Apply(lawsAndHarmonics);
BENCHMARK(ResidualAndJacobian)->Apply(lawsAndHarmonics);
BENCHMARK(ResidualVsSamples)->RangeMultiplier(4)->Range(256, 16384);
BENCHMARK(Condensation)->DenseRange(10, 80, 10);
BENCHMARK(SolverIteration)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80);

}  // namespace

BENCHMARK_MAIN();
