// Every scene in scenes/stress, solved by the shipping pipeline (adaptive refinement, direct
// light by rays, the hemicubes, baking) with default settings, must give finite, non-negative
// radiosities with a balanced energy ledger after every shot, and say why it stopped.
#include <cmath>

#include <gtest/gtest.h>

#include "mesh/scene/readers/scene_loader.h"
#include "tests/solve_support.h"

namespace rad {
namespace {

/// Shots per stress scene: enough to stir up every patch of the stiff ones.
constexpr long kShots = 150;
constexpr double kLedger = 1e-9;

void expectFiniteNonNegative(const std::vector<glm::dvec3>& values, const char* what) {
  for (size_t i = 0; i < values.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(std::isfinite(values[i][k])) << what << " " << i << " channel " << k;
      ASSERT_GE(values[i][k], 0.0) << what << " " << i << " channel " << k;
    }
}

class StressTest : public ::testing::TestWithParam<std::string> {};

TEST_P(StressTest, FiniteNonNegativeAndConservative) {
  Scene scene = loadScene(GetParam());
  SolverBlock flags;
  flags.maxShots = kShots;
  const Settings settings = resolveSettings(scene, flags);
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  RadiositySolve solve(meshed);
  const ProgressiveSolver& solver = solve.solver();
  while (solve.step()) {
    const EnergyLedger& l = solver.ledger();
    glm::dvec3 gap = l.emitted - l.absorbed - l.escaped - l.unshot;
    for (int k = 0; k < 3; ++k) ASSERT_LE(std::abs(gap[k]), kLedger * solver.powerShot() + 1e-300);
  }
  EXPECT_NE(solver.stopReason(), ProgressiveSolver::Stop::None);
  expectFiniteNonNegative(solver.radiosity(), "element");
  EXPECT_LE(solver.ledger().residual(), kLedger);
  // What the result file would show: baked elements and the vertices' display equation.
  const Solution solution = solve.bake();
  expectFiniteNonNegative(solution.B, "baked element");
  expectFiniteNonNegative(shownAtVertices(meshed, solution), "vertex");
}

INSTANTIATE_TEST_SUITE_P(Scenes, StressTest, ::testing::ValuesIn(test::sceneFiles("scenes/stress")),
                         [](const auto& info) { return test::sceneName(info.param); });

}  // namespace
}  // namespace rad
