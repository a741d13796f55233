// A scene text solved as `eqhb solve` solves it: for tests whose scenes need
// the default path (coarse start, fallbacks) rather than the bare solver.
// Link the test with eqhb_app.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "eqhb/app/solve.h"
#include "eqhb/scenes/law_rho.h"
#include "eqhb/scenes/scene.h"

namespace eqhb::test {

// [x; λ] of `text`, read as the file `source`, on the default solve path.
inline Eigen::VectorXd solvedAsTheCommandSolves(const std::string& text, const std::string& source) {
  app::SceneSettings settings;
  settings.path = source;
  settings.document = app::SceneSettings::Document{
      [&](const std::vector<std::string>& o) { return parseScene(text, source, o); },
      [&](const std::vector<std::string>& o) { return lawRhosOfText(text, source, o); }};
  const app::HbRun run = app::solveHarmonicBalance(settings, app::SolveOptions());
  EXPECT_TRUE(run.result.converged()) << source;
  return run.full();
}

}  // namespace eqhb::test
