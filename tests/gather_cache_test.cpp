// Which vertices the final gather renders hemicubes at (radiosity/gather/gather_cache.h): Ward's
// weights, a choice that covers every vertex, and a finely tessellated table (the faces of a
// downloaded model, much finer than the scene is meshed) solved at defaults as right as when
// every vertex gathers, from fewer hemicubes.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "radiosity/gather/final_gather.h"
#include "radiosity/gather/gather_cache.h"
#include "radiosity/light/direct_light.h"
#include "tests/solve_support.h"

namespace rad {
namespace {

const std::string kTable = test::kSourceDir + "/tests/data/furnished/fine_table.json";
const std::string kTableReference = test::kSourceDir + "/tests/data/furnished/fine_table_reference.csv";

/// The table's true error at defaults, against its path-traced reference at 140 points on it
/// and on the floor round and under it (measured 0.92 %, reference noise 0.75 %)...
constexpr double kTableRms = 0.015;
/// ...and how far the defaults may be from every vertex gathering: the 0.5 % (measured
/// 0.00 %: 0.92 % either way).
constexpr double kCacheCostsAtMost = 0.005;
/// The share of the table's vertices (as built, before refinement) that take their light from
/// gathering vertices near them at defaults (measured 3 975 of 11 360, 35 %).
constexpr double kTableInterpolatedAtLeast = 0.3;

TEST(GatherCacheTest, WardsWeightInsideTheAccuracyAndNoneOutside) {
  const glm::dvec3 p(0.0), up(0, 1, 0);
  const double R = 2, a = 0.2;
  // ε = distance / R: 0.1 → 1/0.1 − 1/0.2 = 5.
  EXPECT_NEAR(gatherWeight(p, up, R, {0.2, 0, 0}, up, a), 5.0, 1e-12);
  EXPECT_GT(gatherWeight(p, up, R, {0.01, 0, 0}, up, a), gatherWeight(p, up, R, {0.2, 0, 0}, up, a));
  EXPECT_EQ(gatherWeight(p, up, R, {0.4, 0, 0}, up, a), 0.0);    // ε = a: the edge of its reach
  EXPECT_EQ(gatherWeight(p, up, R, {0.1, 0, 0}, -up, a), 0.0);   // facing the other way
  EXPECT_EQ(gatherWeight(p, up, 0, {0.1, 0, 0}, up, a), 0.0);    // no reach
  // Below its plane by more than 5 % of R (0.1): it lies in front of that point (a curve).
  EXPECT_EQ(gatherWeight(p, up, R, {0.1, -0.2, 0}, up, a), 0.0);
  EXPECT_GT(gatherWeight(p, up, R, {0.1, -0.05, 0}, up, a), 0.0);
  // A bend of 0.1 rad costs √(1 − cos 0.1) ≈ 0.0707 of ε.
  const glm::dvec3 bent(std::sin(0.1), std::cos(0.1), 0);
  EXPECT_NEAR(gatherWeight(p, up, R, {0.2, 0, 0}, bent, a), 1 / (0.1 + std::sqrt(1 - std::cos(0.1))) - 5, 1e-9);
}

/// The table's mesh as built, and its vertices that gather (not black).
struct Meshed {
  MeshedScene scene;
  std::vector<int> candidates;
};

Meshed tableMesh() {
  Scene scene = loadSceneToSolve(kTable);
  const Settings settings = resolveSettings(scene, {});
  Meshed m{meshScene(std::move(scene), settings), {}};
  const PatchMesh& base = *m.scene.base;
  const auto rho = vertexReflectance(base);
  for (size_t v = 0; v < rho.size(); ++v)
    if (rho[v] != glm::dvec3(0.0)) m.candidates.push_back(int(v));
  return m;
}

/// A stand-in for the hemicubes: every vertex's nearest surface `R` away; counts the renders.
GatherRender everySeesAt(double R, std::vector<int>& rendered) {
  return [R, &rendered](const std::vector<int>& which, std::vector<double>& nearest) {
    for (int v : which) nearest[size_t(v)] = R, rendered.push_back(v);
    return true;
  };
}

TEST(GatherCacheTest, EveryVertexGathersOrTakesGatheringOnesWithinItsReach) {
  const Meshed m = tableMesh();
  const PatchMesh& base = *m.scene.base;
  const double size = m.scene.scene.diagonal(), a = 0.2, R = 0.5, farthest = 1.0;
  std::vector<int> rendered;
  const GatherCache cache = chooseGathering(base, m.candidates, a, size, farthest, everySeesAt(R, rendered));
  ASSERT_TRUE(cache.complete);
  EXPECT_EQ(int(rendered.size()), cache.gathering);             // each rendered once
  EXPECT_EQ(std::set<int>(rendered.begin(), rendered.end()).size(), rendered.size());
  // Many take their light (measured 5 781 of 11 360 gather: the outlines of the table's thin
  // parts are most of their vertices, and the room's are as far apart as its elements).
  EXPECT_LT(cache.gathering, int(0.6 * double(m.candidates.size())));
  EXPECT_GT(cache.levels, 1);
  for (int v : m.candidates) {
    const auto& from = cache.from[size_t(v)];
    ASSERT_FALSE(from.empty()) << v;
    if (from.size() == 1 && from[0].first == v) {
      EXPECT_EQ(cache.reach[size_t(v)], R);
      continue;
    }
    EXPECT_FALSE(base.seam(TriMesh::VertexHandle(v))) << v;   // the two sides of a contact line gather
    EXPECT_FALSE(base.mesh.is_boundary(TriMesh::VertexHandle(v))) << v;  // and a surface's outline
    double sum = 0;
    const glm::dvec3 p = PatchMesh::toGlm(base.mesh.point(TriMesh::VertexHandle(v)));
    for (const auto& [g, w] : from) {
      sum += w;
      EXPECT_GT(w, 0);
      EXPECT_GT(cache.reach[size_t(g)], 0) << g;                // a gathering one
      const glm::dvec3 q = PatchMesh::toGlm(base.mesh.point(TriMesh::VertexHandle(g)));
      EXPECT_LT(glm::length(p - q), a * R * 1.01) << v << " from " << g;  // within its reach
      // On the same surface.
      EXPECT_EQ(base.surface(base.mesh.vf_range(TriMesh::VertexHandle(v)).begin()->idx()),
                base.surface(base.mesh.vf_range(TriMesh::VertexHandle(g)).begin()->idx()));
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
  // The same mesh chooses the same vertices.
  std::vector<int> again;
  const GatherCache same = chooseGathering(base, m.candidates, a, size, farthest, everySeesAt(R, again));
  EXPECT_EQ(again, rendered);
  EXPECT_EQ(same.from, cache.from);
}

TEST(GatherCacheTest, EveryVertexGathersWhereAsked) {
  const Meshed m = tableMesh();
  const PatchMesh& base = *m.scene.base;
  const double size = m.scene.scene.diagonal();
  std::vector<int> rendered;
  // Accuracy 0: every vertex, in one level.
  GatherCache cache = chooseGathering(base, m.candidates, 0, size, 1.0, everySeesAt(0.5, rendered));
  EXPECT_EQ(cache.gathering, int(m.candidates.size()));
  EXPECT_EQ(rendered, m.candidates);
  // Nothing may interpolate farther than a micrometre: every vertex gathers.
  rendered.clear();
  cache = chooseGathering(base, m.candidates, 0.2, size, 1e-6, everySeesAt(0.5, rendered));
  EXPECT_EQ(cache.gathering, int(m.candidates.size()));
  // Rendering given up: nothing is chosen.
  cache = chooseGathering(base, m.candidates, 0.2, size, 1.0,
                          [](const std::vector<int>&, std::vector<double>&) { return false; });
  EXPECT_FALSE(cache.complete);
  EXPECT_TRUE(cache.from.empty());
}

/// The shipping pipeline on the fine table: right at defaults, as right as with every vertex
/// gathering, from fewer hemicubes.
TEST(GatherCacheTest, AFineTableAtDefaultsAsRightAsEveryVertexGathering) {
  const auto cached = test::solveLikeCli(kTable);
  SolverBlock every;
  every.gatherAccuracy = 0;
  const auto full = test::solveLikeCli(kTable, every);
  const double rmsCached = test::trueError(*cached, kTableReference);
  const double rmsFull = test::trueError(*full, kTableReference);
  EXPECT_LE(rmsCached, kTableRms);
  EXPECT_LE(rmsCached, rmsFull + kCacheCostsAtMost);
  EXPECT_EQ(full->solution.gather.interpolated, 0);
  const double baseVertices = double(full->solution.gather.points - full->solution.gather.ownHemicubes);
  EXPECT_GE(double(cached->solution.gather.interpolated), kTableInterpolatedAtLeast * baseVertices);
  EXPECT_LT(cached->solution.gather.points, full->solution.gather.points);
  // The vertices neither leave the table dark nor bright anywhere: each within 10 % of the full
  // gather's light at the same vertex where that is not dark.
  ASSERT_EQ(cached->shown.size(), full->shown.size());
  double peak = 0;
  for (const auto& b : full->shown) peak = std::max(peak, b.x + b.y + b.z);
  int off = 0;
  for (size_t v = 0; v < full->shown.size(); ++v) {
    const double f = glm::dot(full->shown[v], glm::dvec3(1)), c = glm::dot(cached->shown[v], glm::dvec3(1));
    if (f > 0.01 * peak && std::abs(c / f - 1) > 0.1) ++off;
  }
  EXPECT_EQ(off, 0);
}

}  // namespace
}  // namespace rad
