// The run settings: command-line overrides over the scene's solver block over defaults that
// follow the scene's size.
#include <cmath>

#include <gtest/gtest.h>

#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/settings.h"
#include "radiosity/solve.h"

namespace rad {
namespace {

const std::string kScenes = std::string(RAD_SOURCE_DIR) + "/scenes/";

TEST(SettingsTest, DefaultsFollowTheSceneSize) {
  Scene scene = loadScene(kScenes + "cube.json");
  scene.solver = SolverBlock{};
  Settings s = resolveSettings(scene, SolverBlock{});
  EXPECT_DOUBLE_EQ(s.maxElementEdge, std::sqrt(3.0) / kDefaultElementsPerDiagonal);
  EXPECT_DOUBLE_EQ(s.maxPatchEdge, s.maxElementEdge * kDefaultPatchToElement);
  SolverBlock flags;
  flags.maxElementEdge = 0.2;
  scene.solver.maxElementEdge = 0.3;
  scene.solver.maxPatchEdge = 0.9;
  s = resolveSettings(scene, flags);
  EXPECT_EQ(s.maxElementEdge, 0.2);  // the flag wins over the file
  EXPECT_EQ(s.maxPatchEdge, 0.9);
}

/// The solver's options of a scene's settings, shooting as a solve that is the answer.
SolverOptions answerOptions(const Scene& scene) {
  const Settings settings = resolveSettings(scene, {});
  return solverOptions(settings, settings.shooting(false), 10);
}

/// Shooter clusters are on by default; the scene's solver block and the flag turn them off,
/// and the solver's options follow.
TEST(SettingsTest, ClusterShootersFromFileAndFlag) {
  Scene scene = loadScene(kScenes + "cube.json");
  scene.solver = SolverBlock{};
  EXPECT_TRUE(resolveSettings(scene, {}).clusterShooters);
  EXPECT_TRUE(answerOptions(scene).clusters);
  scene.solver.clusterShooters = false;
  EXPECT_FALSE(resolveSettings(scene, {}).clusterShooters);
  EXPECT_FALSE(answerOptions(scene).clusters);
  SolverBlock flags;
  flags.clusterShooters = true;
  EXPECT_TRUE(resolveSettings(scene, flags).clusterShooters);  // the flag wins over the file
}

/// Shooting resolution follows the unshot power by default, from the finest shooting resolution
/// down (without the gather: 128; the gather's start shoots at 64, which it never goes below);
/// the scene's solver block and the flag turn it off.
TEST(SettingsTest, ResolutionFollowsPowerFromFileAndFlag) {
  Scene scene = loadScene(kScenes + "cube.json");
  scene.solver = SolverBlock{};
  scene.solver.finalGather = false;
  EXPECT_TRUE(resolveSettings(scene, {}).resolutionFollowsPower);
  EXPECT_EQ(answerOptions(scene).followingResolution, kDefaultHemicubeResolution);
  scene.solver.resolutionFollowsPower = false;
  EXPECT_EQ(answerOptions(scene).followingResolution, 0);
  SolverBlock flags;
  flags.resolutionFollowsPower = true;
  EXPECT_TRUE(resolveSettings(scene, flags).resolutionFollowsPower);  // the flag wins over the file
}

/// A quality moves the defaults: a draft's elements 1.6× as long as the scene asks (its own
/// edge too), a coarser gather taking more neighbours' light; a final solve's 1.6× shorter,
/// every vertex gathering. The flag over the file; flags of the settings it moves win over it.
TEST(SettingsTest, QualityMovesTheDefaults) {
  Scene scene = loadScene(kScenes + "cube.json");
  scene.solver = SolverBlock{};
  const Settings normal = resolveSettings(scene, {});
  EXPECT_EQ(normal.quality, Quality::Default);
  SolverBlock draft;
  draft.quality = Quality::Draft;
  Settings s = resolveSettings(scene, draft);
  EXPECT_EQ(s.quality, Quality::Draft);
  EXPECT_DOUBLE_EQ(s.maxElementEdge, normal.maxElementEdge * kQualityElementRatio);
  EXPECT_DOUBLE_EQ(s.maxPatchEdge, s.maxElementEdge * kDefaultPatchToElement);
  EXPECT_EQ(s.gatherResolution, kDraftGatherResolution);
  EXPECT_EQ(s.gatherAccuracy, kDraftGatherAccuracy);
  scene.solver.quality = Quality::Final;
  scene.solver.maxElementEdge = 0.1;
  s = resolveSettings(scene, {});
  EXPECT_DOUBLE_EQ(s.maxElementEdge, 0.1 / kQualityElementRatio);  // the scene's own edge, shorter
  EXPECT_EQ(s.gatherAccuracy, 0.0);
  EXPECT_EQ(s.gatherResolution, kDefaultGatherResolution);
  s = resolveSettings(scene, draft);  // the flag over the file
  EXPECT_DOUBLE_EQ(s.maxElementEdge, 0.1 * kQualityElementRatio);
  draft.maxElementEdge = 0.05;
  draft.gatherResolution = 64;
  draft.gatherAccuracy = 0.1;
  s = resolveSettings(scene, draft);  // the flags of what it moves win
  EXPECT_EQ(s.maxElementEdge, 0.05);
  EXPECT_EQ(s.gatherResolution, 64);
  EXPECT_EQ(s.gatherAccuracy, 0.1);
}

}  // namespace
}  // namespace rad
