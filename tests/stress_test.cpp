// Every scene in scenes/stress must solve to finite, non-negative radiosities with a balanced
// energy ledger, and say why it stopped.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/settings.h"
#include "radiosity/progressive_solver.h"

namespace rad {
namespace {

/// Shots per stress scene: enough to stir up every patch of the stiff ones.
constexpr long kShots = 150;
constexpr double kLedger = 1e-9;

class StressTest : public ::testing::TestWithParam<std::string> {};

TEST_P(StressTest, FiniteNonNegativeAndConservative) {
  Scene scene = loadScene(GetParam());
  Settings settings = resolveSettings(scene, SolverBlock{});
  PatchMesh mesh = buildPatchMesh(scene, settings.mesh());
  HemicubeFactors factors(mesh, settings.hemicubeResolution, scene.diagonal(), settings.seed);
  SolverOptions options;
  options.maxShots = kShots;
  options.overshoot = settings.overshoot;
  options.emitterSamples = settings.emitterSamples;
  options.shooterSamples = settings.shooterSamples;
  ProgressiveSolver solver(mesh, factors, options);
  while (solver.step()) {
    const EnergyLedger& l = solver.ledger();
    glm::dvec3 gap = l.emitted - l.absorbed - l.escaped - l.unshot;
    for (int k = 0; k < 3; ++k) ASSERT_LE(std::abs(gap[k]), kLedger * solver.powerShot() + 1e-300);
  }
  EXPECT_NE(solver.stopReason(), ProgressiveSolver::Stop::None);
  for (const auto& b : solver.radiosity())
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(std::isfinite(b[k]));
      ASSERT_GE(b[k], 0.0);
    }
  EXPECT_LE(solver.ledger().residual(), kLedger);
}

std::vector<std::string> stressScenes() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(RAD_SOURCE_DIR) + "/scenes/stress"))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

INSTANTIATE_TEST_SUITE_P(Scenes, StressTest, ::testing::ValuesIn(stressScenes()),
                         [](const auto& info) {
                           return std::filesystem::path(info.param).stem().string();
                         });

}  // namespace
}  // namespace rad
