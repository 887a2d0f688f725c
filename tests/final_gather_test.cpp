// The final gather at the vertices (radiosity/final_gather.h), through the shipping pipeline:
// the closed furnace comes out exact, the Cornell box's true error against its stored
// path-traced references stays within the measured limits, the elements agree with their
// vertices, and a scene too large for the gather is told so.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "mesh/reference_points.h"
#include "radiosity/final_gather.h"
#include "radiosity/true_error.h"
#include "tests/solve_support.h"

namespace rad {
namespace {

const std::string kDocs = test::kSourceDir + "/docs/";

/// Every vertex and every element of the closed furnace within this share of E/(1 − ρ)
/// (the accurate-vertices issue's targets; measured 0.04 % or better at every ρ).
struct FurnaceCase {
  double rho, limit;
};

class FurnaceGatherTest : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(FurnaceGatherTest, EveryVertexAndElementExact) {
  const FurnaceCase c = GetParam();
  Scene scene = loadSceneToSolve(test::kScenes + "furnace.json");
  for (Material& m : scene.materials) m.reflectance = glm::dvec3(c.rho);
  // The scene's meshing; the progressive solve only starts the gather off, so it may be
  // quick (every patch of the furnace emits, and emitters shoot from 64 points at R = 256).
  SolverBlock flags;
  flags.emitterSamples = 4;
  flags.hemicubeResolution = flags.emitterHemicubeResolution = 64;
  flags.tolerance = 1e-2;
  flags.maxShots = 2000;  // at ρ = 0.99 the unshot power falls slowly; the gather converges anyway
  const Settings settings = resolveSettings(scene, flags);
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  ASSERT_TRUE(meshed.gather);
  ASSERT_FALSE(meshed.direct);  // every patch emits: no rays, the gather takes the emission itself
  const Solution solution = solveRadiosity(meshed);
  ASSERT_TRUE(solution.gathered);
  EXPECT_TRUE(solution.gather.iterated);
  const double exact = 1 / (1 - c.rho);
  double worstVertex = 0, worstElement = 0;
  for (const glm::dvec3& b : *solution.gathered) worstVertex = std::max(worstVertex, std::abs(b.x / exact - 1));
  for (const glm::dvec3& b : solution.B) worstElement = std::max(worstElement, std::abs(b.x / exact - 1));
  EXPECT_LE(worstVertex, c.limit) << "rho " << c.rho;
  EXPECT_LE(worstElement, c.limit) << "rho " << c.rho;
}

INSTANTIATE_TEST_SUITE_P(Reflectances, FurnaceGatherTest,
                         ::testing::Values(FurnaceCase{0.5, 0.005}, FurnaceCase{0.9, 0.01}, FurnaceCase{0.99, 0.02}),
                         [](const ::testing::TestParamInfo<FurnaceCase>& info) {
                           return "rho_" + std::to_string(int(std::lround(100 * info.param.rho)));
                         });

/// The true error of what the default solve shows, against a stored reference; only the
/// points tagged `tag` when it is not empty.
double trueError(const test::Solved& s, const std::string& reference, const std::string& tag = "") {
  std::vector<ReferencePoint> points = readReferenceFile(reference).points;
  if (!tag.empty())
    points.erase(std::remove_if(points.begin(), points.end(), [&](const ReferencePoint& p) { return p.tag != tag; }),
                 points.end());
  return TrueError(s.meshed.mesh, s.meshed.scene, points, reference).measure(s.shown).rms;
}

/// Limits on the Cornell box's true error at default settings, reference noise included
/// (0.79 % and 0.62 % RMS). Measured: 1.69 % at all 300 points, 1.44 % at the 225 placed by
/// area (4.55 % and 4.27 % before the final gather), 4.05 % at 160 points within 50 mm of the
/// blocks (44.3 % before).
constexpr double kCornellAll = 0.02, kCornellArea = 0.02, kCornellNearBlocks = 0.045;

TEST(FinalGatherTest, CornellBoxTrueErrorAtDefaults) {
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json");
  ASSERT_TRUE(s->solution.gathered);
  EXPECT_LE(trueError(*s, kDocs + "cornell_reference.csv"), kCornellAll);
  EXPECT_LE(trueError(*s, kDocs + "cornell_reference.csv", "area"), kCornellArea);
  EXPECT_LE(trueError(*s, kDocs + "cornell_near_blocks_reference.csv"), kCornellNearBlocks);
}

TEST(FinalGatherTest, ElementsShowTheMeanOfTheirVertices) {
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json");
  const PatchMesh& mesh = s->meshed.mesh;
  ASSERT_EQ(s->solution.B.size(), size_t(mesh.elementCount()));
  for (auto f : mesh.mesh.faces()) {
    glm::dvec3 mean(0.0);
    for (auto v : mesh.mesh.fv_range(f)) mean += s->shown[size_t(v.idx())] / 3.0;
    const glm::dvec3 b = s->solution.B[size_t(f.idx())];
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[c], mean[c], 1e-12 * (1 + mean[c])) << "element " << f.idx();
  }
  EXPECT_EQ(s->solution.ambient, glm::dvec3(0.0));
}

TEST(FinalGatherTest, SkippedWithAWarningBeyondItsBudget) {
  Scene scene = loadSceneToSolve(test::kScenes + "stress/slivers.json");
  std::vector<std::string> warnings;
  const Settings settings = resolveSettings(scene, {});
  const MeshedScene meshed =
      meshScene(std::move(scene), settings, {false, [&](const std::string& w) { warnings.push_back(w); }});
  EXPECT_FALSE(meshed.gather);
  EXPECT_GT(double(meshed.mesh.mesh.n_vertices()) * meshed.mesh.elementCount(), kMaxGatherWork);
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(),
                          [](const std::string& w) { return w.find("final gather skipped") != std::string::npos; }));
}

TEST(FinalGatherTest, SettingOffKeepsTheProgressiveSolution) {
  SolverBlock flags;
  flags.finalGather = false;
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json", flags);
  EXPECT_FALSE(s->meshed.gather);
  EXPECT_FALSE(s->solution.gathered);
}

}  // namespace
}  // namespace rad
