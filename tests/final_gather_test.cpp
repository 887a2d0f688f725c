// The final gather at the vertices (radiosity/gather/final_gather.h), through the shipping pipeline:
// the closed furnace comes out exact, the Cornell box's true error against its stored
// path-traced references stays within the measured limits, the elements agree with their
// vertices, and a scene too large for the gather is told so.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/results/reference_points.h"
#include "radiosity/formfactors/flat_regions.h"
#include "radiosity/gather/final_gather.h"
#include "mesh/refine.h"
#include "radiosity/gather/gather_points.h"
#include "radiosity/true_error.h"
#include "tests/solve_support.h"

namespace rad {
namespace {

using test::kReferences;
using test::trueError;
using test::trueErrorOf;

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
  // The scene's settings: the progressive solve only starts the gather off (a tenth of a shot per patch).
  const Settings settings = resolveSettings(scene, {});
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  ASSERT_TRUE(meshed.gather.on);
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

/// Limits on the Cornell box's true error at default settings (the accurate-vertices issue's
/// targets), reference noise included (0.79 % and 0.62 % RMS). Measured: 1.56 % at all 300
/// points, 1.39 % at the 225 placed by area (4.55 % and 4.27 % before the final gather), 3.82 %
/// at 160 points within 50 mm of the blocks (44.3 % before).
constexpr double kCornellAll = 0.02, kCornellArea = 0.02, kCornellNearBlocks = 0.04;

TEST(FinalGatherTest, CornellBoxTrueErrorAtDefaults) {
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json");
  ASSERT_TRUE(s->solution.gathered);
  EXPECT_LE(trueError(*s, kReferences + "cornell_reference.csv"), kCornellAll);
  EXPECT_LE(trueError(*s, kReferences + "cornell_reference.csv", "area"), kCornellArea);
  EXPECT_LE(trueError(*s, kReferences + "cornell_near_blocks_reference.csv"), kCornellNearBlocks);
}

/// The doorway scene (scenes/doorway.json): the room behind the doorway, lit only through it,
/// against its path-traced reference (tests/data/references/doorway_reference.csv, 1 % noise), at default
/// settings. The targets: no bias beyond ±1 % in any channel, RMS ≤ 3 % over the
/// room's area-stratified points. The doorway's jambs (kept by the contact cutter) within 3 %,
/// its lintel (6 points) within 5 %. Measured: room 1.7 % RMS, channel means −0.4 to −0.2 %;
/// jambs 1.0 %; lintel 3.8 % (one point in its corner with a jamb −9 %, where the
/// indirect light changes within the 100 mm reveal faster than its vertices follow). The
/// floor strip behind the doorway (tag doorway_floor, 3.7 %) lies in the lamp's sharp
/// penumbrae and is not held to these.
constexpr double kDoorwayRoomBias = 0.01, kDoorwayRoomRms = 0.03, kDoorwayJambRms = 0.03, kDoorwayLintelRms = 0.05;

TEST(FinalGatherTest, RoomBehindADoorwayAtDefaults) {
  const auto s = test::solveLikeCli(test::kScenes + "doorway.json");
  ASSERT_TRUE(s->solution.gathered);
  const ErrorSummary room = trueErrorOf(*s, kReferences + "doorway_reference.csv", "roomB_");
  EXPECT_GE(room.used, 500);
  EXPECT_LE(room.rms, kDoorwayRoomRms);
  for (int c = 0; c < 3; ++c) EXPECT_LE(std::abs(room.meanRgb[c]), kDoorwayRoomBias) << "channel " << c;
  for (const char* jamb : {"doorway_jamb_left", "doorway_jamb_right"})
    EXPECT_LE(trueError(*s, kReferences + "doorway_reference.csv", jamb), kDoorwayJambRms) << jamb;
  EXPECT_LE(trueError(*s, kReferences + "doorway_reference.csv", "doorway_lintel"), kDoorwayLintelRms);
}

/// McGuire's CornellBox-Original from its one-line scene (scenes/cornell_original.json), at
/// default settings, against its path-traced reference (tests/data/references/cornell_original_reference.csv:
/// 300 points, seed 1, the reference's defaults). Measured: 1.53 % RMS; the limit leaves room
/// for the reference's own noise (about 0.8 %) and a seed's worth of hemicube noise.
constexpr double kCornellOriginalRms = 0.02;

TEST(FinalGatherTest, CornellBoxOriginalFromItsMeshFileTrueErrorAtDefaults) {
  const auto s = test::solveLikeCli(test::kScenes + "cornell_original.json");
  ASSERT_TRUE(s->solution.gathered);
  EXPECT_LE(trueError(*s, kReferences + "cornell_original_reference.csv"), kCornellOriginalRms);
}

/// The gather's hemicubes rendered beside the rays and the shots (GatherAhead, as `radiosity
/// solve` does) give what the gather rendering them itself gives, bit for bit: they draw the
/// mesh as built before refinement, from its own vertices.
TEST(FinalGatherTest, HemicubesRenderedAheadGiveTheSameLight) {
  auto solved = [](bool ahead) {
    Scene scene = loadSceneToSolve(test::kScenes + "cornell_original.json");
    const Settings settings = resolveSettings(scene, {});
    auto meshed = std::make_unique<MeshedScene>(meshScene(std::move(scene), settings, {true, nullptr, ahead}));
    EXPECT_EQ(bool(meshed->gather.ahead), ahead);
    EXPECT_TRUE(meshed->base);  // refined: the hemicubes draw the mesh before
    const Solution solution = solveRadiosity(*meshed);
    return std::make_pair(*solution.gathered, solution.gather);
  };
  const auto [ahead, aheadStats] = solved(true);
  const auto [inPlace, inPlaceStats] = solved(false);
  EXPECT_EQ(aheadStats.factors, inPlaceStats.factors);
  EXPECT_EQ(aheadStats.iterations, inPlaceStats.iterations);
  ASSERT_EQ(ahead.size(), inPlace.size());
  size_t same = 0;
  for (size_t v = 0; v < ahead.size(); ++v) same += ahead[v] == inPlace[v];
  EXPECT_EQ(same, ahead.size());
}

/// Where the gather renders: on the refined Cornell box, the vertices of the mesh before
/// refinement and those refinement added beside another surface (nearSurfaces), and no other;
/// every other vertex takes a convex combination of gathering vertices of its own surface,
/// which reproduces a linear field exactly (barycentric weights in its base element).
TEST(FinalGatherTest, RefinedVerticesInterpolateTheBaseVertices) {
  Scene scene = loadSceneToSolve(test::kScenes + "cornell.json");
  const Settings settings = resolveSettings(scene, {});
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  ASSERT_TRUE(meshed.base);
  const PatchMesh& mesh = meshed.mesh;
  const GatherPoints g = gatherPoints(mesh, meshed.base.get(), vertexReflectance(mesh), &meshed.ownHemicube);
  const size_t own = size_t(ownHemicubes(meshed));
  EXPECT_GT(own, 0u);
  EXPECT_EQ(size_t(g.count()), meshed.base->mesh.n_vertices() + own);
  EXPECT_LT(size_t(g.count()), mesh.mesh.n_vertices() * 3 / 4);
  auto at = [&](size_t v) {
    const auto& p = mesh.mesh.point(TriMesh::VertexHandle(int(v)));
    return glm::dvec3(p[0], p[1], p[2]);
  };
  std::vector<glm::dvec3> linear(mesh.mesh.n_vertices());
  for (size_t v = 0; v < linear.size(); ++v) linear[v] = glm::dvec3(1 + 0.003 * at(v).x - 0.002 * at(v).y + 0.001 * at(v).z);
  std::vector<glm::dvec3> onlyGathered(linear.size(), glm::dvec3(0.0));
  for (size_t v = 0; v < linear.size(); ++v)
    if (g.at[v]) onlyGathered[v] = linear[v];
  const std::vector<glm::dvec3> spread = g.spread(onlyGathered);
  const std::vector<glm::dvec3> rho = vertexReflectance(mesh);
  for (size_t v = 0; v < linear.size(); ++v) {
    double sum = 0;
    for (const auto& [p, w] : g.from[v]) {
      ASSERT_TRUE(g.at[size_t(p)]);
      ASSERT_GT(w, 0);
      ASSERT_EQ(rho[size_t(p)], rho[v]);  // the same surface's
      sum += w;
    }
    ASSERT_NEAR(sum, 1, 1e-12) << v;
    ASSERT_NEAR(spread[v].x, linear[v].x, 1e-9) << v;
  }
}

/// The distance from p to the triangle (a, b, c): to its plane where p projects inside it,
/// else to the nearest of its edges.
double distanceToTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
  const glm::dvec3 q = p - n * glm::dot(p - a, n);
  const bool inside = glm::dot(glm::cross(b - a, q - a), n) >= 0 && glm::dot(glm::cross(c - b, q - b), n) >= 0 &&
                      glm::dot(glm::cross(a - c, q - c), n) >= 0;
  if (inside) return std::abs(glm::dot(p - a, n));
  auto toSegment = [&](const glm::dvec3& u, const glm::dvec3& w) {
    const double t = std::clamp(glm::dot(p - u, w - u) / glm::dot(w - u, w - u), 0.0, 1.0);
    return glm::length(p - (u + t * (w - u)));
  };
  return std::min({toSegment(a, b), toSegment(b, c), toSegment(c, a)});
}

/// The vertices refinement added that gather through their own hemicubes have another surface
/// within their reach (their base element's longest edge; checked against every element of
/// another surface side); some are left to interpolate; and on the floor under a sofa standing
/// 6 mm above it every vertex refinement added gathers.
TEST(FinalGatherTest, OwnHemicubesWhereAnotherSurfaceIsNear) {
  Scene scene = loadSceneToSolve(test::kScenes + "cornell.json");
  const Settings settings = resolveSettings(scene, {});
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  const PatchMesh& mesh = meshed.mesh;
  ASSERT_EQ(meshed.ownHemicube.size(), mesh.mesh.n_vertices());
  size_t own = 0;
  for (auto v : mesh.mesh.vertices()) {
    if (!meshed.ownHemicube[size_t(v.idx())] || own++ % 7) continue;  // every 7th checked
    double reach = 0;
    int side = -1;
    for (auto f : mesh.mesh.vf_range(v)) {
      reach = std::max(reach, longestEdge(*meshed.base, mesh.base(f.idx())));
      side = mesh.surface(f.idx()) * 2 + mesh.side(f.idx());
    }
    const glm::dvec3 p = PatchMesh::toGlm(mesh.mesh.point(v));
    double nearest = HUGE_VAL;
    for (int e = 0; e < mesh.elementCount(); ++e) {
      if (mesh.surface(e) * 2 + mesh.side(e) == side) continue;
      const auto c = mesh.corners(e);
      nearest = std::min(nearest, distanceToTriangle(p, c[0], c[1], c[2]));
    }
    ASSERT_LE(nearest, reach * (1 + 1e-6)) << v.idx();
  }
  const size_t added = mesh.mesh.n_vertices() - meshed.base->mesh.n_vertices();
  EXPECT_GT(own, added / 10);
  EXPECT_LT(own, added * 9 / 10);

  Scene gap = loadSceneToSolve(test::kData + "piercing/narrow_gap.json");
  const Settings gapSettings = resolveSettings(gap, {});
  const MeshedScene underSofa = meshScene(std::move(gap), gapSettings);
  ASSERT_TRUE(underSofa.base);
  const PatchMesh& m = underSofa.mesh;
  size_t under = 0;
  for (auto v : m.mesh.vertices()) {
    const glm::dvec3 p = PatchMesh::toGlm(m.mesh.point(v));
    const bool floor = p.y == 0 && std::abs(p.x) < 0.79 && p.z > 0.41 && p.z < 1.19;
    if (!floor || size_t(v.idx()) < underSofa.base->mesh.n_vertices()) continue;
    ++under;
    EXPECT_TRUE(underSofa.ownHemicube[size_t(v.idx())]) << p.x << " " << p.z;
  }
  EXPECT_GT(under, 0u);
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

TEST(FinalGatherTest, LeftOutWithAWarningBeyondItsBudget) {
  GatherEstimate estimate;
  estimate.located = (kMaxGatherSeconds + 1) / kGatherSecondsPerLocatedPixel;
  const std::string over = gatherLeftOut(estimate, 2, 0, 0);
  EXPECT_NE(over.find("final gather skipped"), std::string::npos) << over;
  EXPECT_NE(over.find("on one core"), std::string::npos) << over;
  estimate.located /= 2;
  EXPECT_EQ(gatherLeftOut(estimate, 2, 0, 0), "");
  // With a time limit: at most half of what meshing left.
  const double seconds = estimate.seconds(2);
  EXPECT_EQ(gatherLeftOut(estimate, 2, 2 * seconds + 1, 1e5), "");
  const std::string late = gatherLeftOut(estimate, 2, 2 * seconds - 1, 1e5);
  EXPECT_NE(late.find("the time limit leaves after meshing"), std::string::npos) << late;
  EXPECT_NE(gatherLeftOut(estimate, 2, 1e-9, 300).find("and no shot"), std::string::npos);
  estimate.located *= 4;  // over the budget too: still no shot is what happens
  EXPECT_NE(gatherLeftOut(estimate, 2, 1e-9, 300).find("and no shot"), std::string::npos);
}

/// A 95 000-element box whose hemicubes would have drawn every element (4.7e9 vertex-element
/// pairs, over the budget: it was shot at the full defaults instead) draws six walls' outlines:
/// the gather is cheap and runs.
TEST(FinalGatherTest, AFineBoxDrawsItsWallsOutlines) {
  Scene scene = loadSceneToSolve(test::kData + "fine_box.json");
  const Settings settings = resolveSettings(scene, {});
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  EXPECT_TRUE(meshed.gather.on);
  const double vertices = double(meshed.mesh.mesh.n_vertices());
  EXPECT_GT(vertices, 40000);
  EXPECT_LT(meshed.gather.estimate.drawn, 20 * vertices);
  // 12 s on one core (1.5e8 pixels resolved); drawing every element, 4.7e9 pairs were 141 s.
  EXPECT_LT(meshed.gather.estimate.seconds(1), 30);
}

/// Where a hemicube sees most of the scene (the Cornell box) it does not cull: the gather
/// sorts every triangle it draws to its faces from every gathering vertex, and resolves more
/// than a top face's worth of pixels in each (the box is closed but for its front).
TEST(FinalGatherTest, WorkIsWhatTheHemicubesDraw) {
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json");
  ASSERT_TRUE(s->meshed.gather.on);
  const PatchMesh& base = *s->meshed.base;
  const double points = double(s->solution.gather.points);
  const FlatRegions regions(base, s->meshed.scene.diagonal());
  EXPECT_LT(regions.drawn().elementCount() * 20, size_t(base.elementCount()));
  // How many vertices gather is estimated (kGatherCoverShare): measured 3.5 % under.
  EXPECT_NEAR(s->meshed.gather.estimate.drawn / (points * double(regions.drawn().elementCount())), 1.0, 0.1);
  const int R = kDefaultGatherResolution;
  EXPECT_GT(s->meshed.gather.estimate.located, points * R * R);
}

/// With rows that fit its memory, the gather is iterated to its own solution from any start:
/// the start shoots at most kGatherStartMaxShots times however many patches there are.
TEST(FinalGatherTest, IteratedGatherStartsFromAHundredShotsAtMost) {
  Scene scene = loadSceneToSolve(test::kData + "four_lamps.json");
  SolverBlock flags;
  flags.maxElementEdge = 0.06;
  flags.maxPatchEdge = 0.03;  // a patch per element: over ten thousand patches
  const Settings settings = resolveSettings(scene, flags);
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  ASSERT_TRUE(meshed.gather.on);
  ASSERT_TRUE(meshed.gather.estimate.iterates(GatherOptions{}));
  const double patches = double(meshed.mesh.patches.size());
  EXPECT_GT(kIteratedStartShotsPerPatch * patches, double(kGatherStartMaxShots));
  EXPECT_NEAR(meshed.gather.shooting.shotsPerPatch * patches, double(kGatherStartMaxShots), 1e-6);
}

/// A time limit that meshing alone uses up: no gather and no shot, but a result to look at
/// (the rays' direct light and the ambient term of all the light not shot), said in a warning.
TEST(FinalGatherTest, TimeLimitSpentByMeshingStillGivesAViewableResult) {
  SolverBlock flags;
  flags.timeLimit = 1e-6;
  Scene scene = loadSceneToSolve(test::kScenes + "cornell.json");
  std::vector<std::string> warnings;
  const Settings settings = resolveSettings(scene, flags);
  const MeshedScene meshed = meshScene(std::move(scene), settings,
                                       {true, [&](const std::string& w) { warnings.push_back(w); }});
  EXPECT_FALSE(meshed.gather.on);
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(),
                          [](const std::string& w) { return w.find("meshing took all") != std::string::npos; }));
  RadiositySolve solve(meshed);
  while (solve.step()) {
  }
  EXPECT_EQ(solve.solver().stopReason(), ProgressiveSolver::Stop::TimeLimit);
  const Solution solution = solve.bake();
  EXPECT_FALSE(solution.gathered);
  EXPECT_FALSE(solution.converged);
  EXPECT_GT(solution.ambient.x, 0.0);
  const std::vector<glm::dvec3> shown = shownAtVertices(meshed, solution);
  for (const glm::dvec3& x : shown)
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(x[c]) && x[c] >= 0) << x[c];
}

/// A gather whose deadline has passed gives up (empty, timed out) instead of running over.
TEST(FinalGatherTest, GivesUpAtItsDeadline) {
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json");
  GatherOptions options;
  options.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  GatherStats stats;
  const std::vector<glm::dvec3> start(s->meshed.mesh.mesh.n_vertices(), glm::dvec3(0.0));
  const auto gathered = finalGather(s->meshed.mesh, s->meshed.base.get(), s->meshed.scene.diagonal(), start,
                                    nullptr, options, &stats);
  EXPECT_TRUE(gathered.empty());
  EXPECT_TRUE(stats.timedOut);
}

/// Past the deadline with the base mesh's rows rendered ahead, the vertices refinement added
/// interpolate their base corners instead of rendering hemicubes of their own: the gather gives
/// what it gives without them, rather than nothing.
TEST(FinalGatherTest, AtItsDeadlineAddedVerticesInterpolate) {
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json");
  ASSERT_TRUE(s->meshed.base);
  ASSERT_GT(ownHemicubes(s->meshed), 0);
  GatherOptions options;
  const GatherRows ahead = renderGatherRows(*s->meshed.base, s->meshed.scene.diagonal(), options);
  ASSERT_TRUE(ahead.kept);
  options.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  const std::vector<glm::dvec3> start = *s->solution.gathered;
  GatherStats withStats, withoutStats;
  const auto with = finalGather(s->meshed.mesh, s->meshed.base.get(), s->meshed.scene.diagonal(), start, nullptr,
                                options, &withStats, &ahead, &s->meshed.ownHemicube);
  const auto without = finalGather(s->meshed.mesh, s->meshed.base.get(), s->meshed.scene.diagonal(), start,
                                   nullptr, options, &withoutStats, &ahead);
  EXPECT_FALSE(withStats.timedOut);
  EXPECT_EQ(withStats.ownHemicubes, 0);
  EXPECT_EQ(withStats.points, withoutStats.points);
  ASSERT_FALSE(with.empty());
  EXPECT_EQ(with, without);
}

/// Rows rendered ahead that outgrow the memory budget stop rendering (they are let go: without
/// the start they cannot be gathered as they come), and the gather renders them again, gathered
/// once over the start: what it gives without rows rendered ahead, bit for bit.
TEST(FinalGatherTest, RowsRenderedAheadOverTheBudgetAreRenderedAgain) {
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json");
  ASSERT_TRUE(s->meshed.base);
  GatherOptions options;
  options.memoryBytes = 100000;  // some 12 000 factors: a few rows
  const GatherRows ahead = renderGatherRows(*s->meshed.base, s->meshed.scene.diagonal(), options);
  EXPECT_FALSE(ahead.kept);
  EXPECT_TRUE(ahead.rows.empty());
  EXPECT_LT(ahead.factors, 20 * 12000);  // stopped soon after the budget, not at every vertex
  const std::vector<glm::dvec3> start = *s->solution.gathered;
  GatherStats withStats, withoutStats;
  const auto with = finalGather(s->meshed.mesh, s->meshed.base.get(), s->meshed.scene.diagonal(), start, nullptr,
                                options, &withStats, &ahead);
  const auto without = finalGather(s->meshed.mesh, s->meshed.base.get(), s->meshed.scene.diagonal(), start,
                                   nullptr, options, &withoutStats);
  EXPECT_FALSE(withStats.iterated);
  EXPECT_FALSE(withStats.renderedAhead);
  EXPECT_EQ(with, without);
}

TEST(FinalGatherTest, SettingOffKeepsTheProgressiveSolution) {
  SolverBlock flags;
  flags.finalGather = false;
  const auto s = test::solveLikeCli(test::kScenes + "cornell.json", flags);
  EXPECT_FALSE(s->meshed.gather.on);
  EXPECT_FALSE(s->solution.gathered);
}

}  // namespace
}  // namespace rad
