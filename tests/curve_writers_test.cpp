#include "eqhb/curves/curve_writers.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "eqhb/backends/registry.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

bool exists(const std::string& path) { return std::ifstream(path).good(); }

// Duffing without fallbacks loses the grid points past its upper fold.
Curve duffingWithFailures(const Scene& scene) {
  auto solver = makeSolver("dogleg");
  ContinuationOptions options;
  options.from = *scene.sweep_from;
  options.to = *scene.sweep_to;
  options.fallbacks = FallbackChain();
  return sweepSequential(scene.model, *solver, {}, options);
}

TEST(CurveWriters, SplitKeepsTheRunsOrderAndIndexesTheConvergedPoints) {
  Curve curve;
  for (bool ok : {true, false, true, false, false, true}) {
    CurvePoint p;
    p.converged = ok;
    p.omega = static_cast<double>(curve.points.size());
    curve.points.push_back(p);
  }
  const CurveParts parts = splitCurve(curve);
  ASSERT_EQ(parts.converged.size(), 3u);
  ASSERT_EQ(parts.failed.size(), 3u);
  EXPECT_EQ(parts.converged[1]->omega, 2.0);
  EXPECT_EQ(parts.failed[2]->omega, 4.0);
  EXPECT_EQ(parts.curve_index, (std::vector<int>{0, -1, 1, -1, -1, 2}));
}

TEST(CurveWriters, FailedPointsGoToTheCompanionFileNotToNanRows) {
  const Scene scene = loadScene(test::problem("duffing.toml"));
  const Curve curve = duffingWithFailures(scene);
  ASSERT_GT(curve.failed_points, 0);
  const std::string path = ::testing::TempDir() + "curve_writers_test.csv";
  const std::string failed_path = failedCurvePath(path);
  EXPECT_EQ(failed_path, ::testing::TempDir() + "curve_writers_test.failed.csv");
  writeCurveCsv(path, curve, scene.model.structure.dofs());
  const std::vector<std::string> rows = lines(path), failed = lines(failed_path);
  ASSERT_EQ(rows.size(), curve.points.size() - curve.failed_points + 1);
  for (size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].find("nan"), std::string::npos) << rows[i];
    EXPECT_NE(rows[i].find(",true,"), std::string::npos) << rows[i];
  }
  ASSERT_EQ(failed.size(), static_cast<size_t>(curve.failed_points) + 1);
  EXPECT_EQ(failed[0], "omega,termination,iterations,residual_evaluations,jacobian_evaluations,residual_norm,seconds");
  const CurveParts parts = splitCurve(curve);
  for (size_t i = 0; i < parts.failed.size(); ++i) {
    std::ostringstream start;
    start.precision(10);
    start << parts.failed[i]->omega << ",\"" << parts.failed[i]->termination << "\",";
    EXPECT_EQ(failed[i + 1].rfind(start.str(), 0), 0u) << failed[i + 1];
  }
  // A later curve without failures leaves no stale list behind.
  Curve whole;
  for (const CurvePoint* p : parts.converged) whole.points.push_back(*p);
  writeCurveCsv(path, whole, scene.model.structure.dofs());
  EXPECT_FALSE(exists(failed_path));
  EXPECT_EQ(lines(path).size(), rows.size());
  std::remove(path.c_str());
}

TEST(CurveWriters, TheSummaryListsTheFailedPoints) {
  const Scene scene = loadScene(test::problem("duffing.toml"));
  const Curve curve = duffingWithFailures(scene);
  CurveRun run;
  run.scene = scene.name;
  run.solver = "dogleg";
  run.from = *scene.sweep_from;
  run.to = *scene.sweep_to;
  run.model = &scene.model;
  std::ostringstream text;
  writeCurveSummary(text, curve, run);
  // Duffing's lost points are neighbours that failed alike: one line.
  const CurveParts parts = splitCurve(curve);
  std::ostringstream run_line;
  run_line << "failed at omega = " << parts.failed.front()->omega << " to " << parts.failed.back()->omega << ", "
           << parts.failed.size() << " points: " << parts.failed.front()->termination << "\n";
  EXPECT_NE(text.str().find(run_line.str()), std::string::npos) << text.str();
  EXPECT_NE(text.str().find(std::to_string(curve.failed_points) + " failed"), std::string::npos) << text.str();
}

}  // namespace
}  // namespace eqhb
