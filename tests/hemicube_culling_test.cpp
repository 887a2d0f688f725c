// The hemicube's culling: its parts (index set, depth pyramid, element hierarchy) against
// brute force, and whole hemicubes culled against the same ones drawing every element.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/formfactors/element_hierarchy.h"
#include "radiosity/formfactors/hemicube.h"
#include "radiosity/formfactors/hemicube_culling.h"
#include "radiosity/formfactors/hemicube_depth_pyramid.h"
#include "radiosity/formfactors/hemicube_index_set.h"
#include "tests/room_grid.h"
#include "tests/support.h"

namespace rad {
namespace {

using test::kScenes;

// ---- Parts ----------------------------------------------------------------------------------

TEST(IndexSetTest, DrainsInAscendingOrderAndEmpties) {
  IndexSet set;
  set.resize(300000);
  std::vector<uint32_t> in = {299999, 5, 4096, 64, 63, 5, 0, 262143, 262144, 4095};
  for (uint32_t i : in) set.insert(i);
  std::vector<uint32_t> out;
  set.drain([&](uint32_t i) { out.push_back(i); });
  std::sort(in.begin(), in.end());
  in.erase(std::unique(in.begin(), in.end()), in.end());
  EXPECT_EQ(out, in);
  out.clear();
  set.drain([&](uint32_t i) { out.push_back(i); });
  EXPECT_TRUE(out.empty());
}

/// Every pixel of rect deeper than `depth`, pixel by pixel.
bool coversByPixel(const std::vector<float>& depth, int width, const PixelRect& r, float d) {
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x)
      if (!(depth[size_t(y) * size_t(width) + size_t(x)] > d)) return false;
  return true;
}

TEST(DepthPyramidTest, CoversExactlyWhenEveryPixelIsNearer) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int agreed = 0, covered = 0;
  for (auto [width, height] : std::vector<std::pair<int, int>>{{64, 64}, {64, 32}, {6, 3}, {2, 1}, {33, 17}}) {
    // Depths in smooth blobs with some empty (0) pixels, so that both answers occur.
    std::vector<float> depth(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        depth[size_t(y) * size_t(width) + size_t(x)] = unit(rng) < 0.02f ? 0.0f : 0.5f + 0.4f * std::sin(0.3f * x) * std::cos(0.2f * y);
    DepthPyramid pyramid;
    pyramid.build(depth.data(), width, height);
    for (int trial = 0; trial < 2000; ++trial) {
      std::uniform_int_distribution<int> xs(0, width - 1), ys(0, height - 1);
      int x0 = xs(rng), x1 = xs(rng), y0 = ys(rng), y1 = ys(rng);
      if (trial % 2) x1 = std::min(width - 1, x0 + trial % 4), y1 = std::min(height - 1, y0 + trial % 3);
      const PixelRect r{std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
      const float d = unit(rng) * 0.6f;
      const bool expected = coversByPixel(depth, width, r, d);
      ASSERT_EQ(pyramid.covers(r, d), expected)
          << width << "x" << height << " rect [" << r.x0 << "," << r.x1 << "]x[" << r.y0 << "," << r.y1 << "] depth " << d;
      ++agreed, covered += expected;
    }
  }
  EXPECT_GT(covered, agreed / 20) << "the trials should cover both answers";
  EXPECT_LT(covered, agreed - agreed / 20);
}

TEST(ElementHierarchyTest, EveryElementOnceInLeavesWithinTheirBoxes) {
  const test::RoomGrid grid{2, 2};
  const HemicubeGeometry g = test::roomGrid(grid);
  const ElementHierarchy h(g.positions, g.indices, g.normals);
  std::vector<int> seen(g.elementCount(), 0);
  const auto& nodes = h.nodes();
  for (size_t k = 0; k < nodes.size(); ++k) {
    const auto& node = nodes[k];
    for (uint32_t i = node.first; i < node.first + node.count; ++i)
      for (int c = 0; c < 3; ++c) {
        const glm::dvec3& p = g.positions[g.indices[3 * size_t(h.order()[i]) + size_t(c)]];
        ASSERT_TRUE(glm::all(glm::lessThanEqual(node.lo, p)) && glm::all(glm::lessThanEqual(p, node.hi)))
            << "node " << k << ", element " << h.order()[i];
      }
    if (node.leaf()) {
      EXPECT_LE(node.count, ElementHierarchy::kLeafSize);
      for (uint32_t i = node.first; i < node.first + node.count; ++i) {
        const uint32_t e = h.order()[i];
        ++seen[e];
        // The leaf's copies of the element's corners and normal.
        EXPECT_EQ(h.normals()[i], g.normals[e]);
        for (size_t c = 0; c < 3; ++c) {
          ASSERT_LT(h.corners()[i][c], node.vertexCount);
          EXPECT_EQ(h.leafPositions()[node.vertexFirst + h.corners()[i][c]], g.positions[g.indices[3 * e + c]]);
        }
      }
      continue;
    }
    // The children split the node's elements.
    const auto &a = nodes[k + 1], &b = nodes[node.second];
    EXPECT_EQ(a.first, node.first);
    EXPECT_EQ(b.first, a.first + a.count);
    EXPECT_EQ(a.count + b.count, node.count);
  }
  EXPECT_EQ(nodes[0].count, g.elementCount());
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(g.elementCount()));
}

/// Five faces' depths as a cube at the origin looking up +z (rotation 0) holds them when a
/// wall at height `wall` covers its top face where x < `edge` (in the face's [-1, 1]), and
/// nothing else was drawn.
struct WallDepths {
  static constexpr int kR = 32;
  static constexpr double kNear = 1e-3;
  HemicubeFrame frame = HemicubeFrame::make({0, 0, 0}, {0, 0, 1}, 0, 0);
  std::array<std::vector<float>, 5> depth;
  std::array<DepthPyramid, 5> pyramids;

  WallDepths(double wall, double edge) {
    for (int f = 0; f < 5; ++f) depth[size_t(f)].assign(size_t(kR) * (f == 0 ? kR : kR / 2), 0.0f);
    for (int j = 0; j < kR; ++j)
      for (int i = 0; i < kR; ++i)
        if (-1 + (i + 0.5) * 2.0 / kR < edge) depth[0][size_t(j) * kR + size_t(i)] = float(kNear / wall);
    for (int f = 0; f < 5; ++f) pyramids[size_t(f)].build(depth[size_t(f)].data(), kR, f == 0 ? kR : kR / 2);
  }
  /// Whether the box [lo, hi] (given in the cube's frame u, v, n) is hidden.
  bool hidden(const glm::dvec3& lo, const glm::dvec3& hi) const {
    const glm::dvec3 a = lo.x * frame.u + lo.y * frame.v + lo.z * frame.n;
    const glm::dvec3 b = hi.x * frame.u + hi.y * frame.v + hi.z * frame.n;
    return boxHidden(frame, glm::min(a, b), glm::max(a, b), {pyramids, kR, kNear});
  }
};

TEST(BoxCullingTest, HiddenOnlyWhollyBehindWhatCoversItsPixels) {
  const WallDepths all(10, 2), half(10, 0);  // the wall over the whole top face, or x < 0
  // Seen on the top face only (|x|, |y| < z): hidden just behind the wall, not just before.
  EXPECT_TRUE(all.hidden({-1, -1, 10.1}, {1, 1, 11}));
  EXPECT_FALSE(all.hidden({-1, -1, 9.9}, {1, 1, 11}));
  EXPECT_FALSE(all.hidden({-1, -1, 10.0}, {1, 1, 11})) << "touching the wall: within the depth margin";
  // Behind the half wall: hidden where it covers, not where a pixel still shows the sky.
  EXPECT_TRUE(half.hidden({-4, -1, 10.1}, {-1, 1, 11}));
  EXPECT_FALSE(half.hidden({-4, -1, 10.1}, {0.5, 1, 11}));
  // Reaching a side face, where nothing was drawn.
  EXPECT_FALSE(all.hidden({-1, -1, 10.1}, {12, 1, 11}));
  // Reaching the eye's near plane on the top face.
  EXPECT_FALSE(all.hidden({-1, -1, 0}, {1, 1, 11}));
}

TEST(BoxCullingTest, BelowTheBaseOnlyWhenNoPointIsAbove) {
  const HemicubeFrame frame = HemicubeFrame::make({1, 2, 3}, glm::normalize(glm::dvec3(1, 1, 0)), 0.3, 0);
  // The base plane x + y = 3 through the eye.
  EXPECT_TRUE(boxBelowBase(frame, {-5, -5, -5}, {1, 1.9, 5}));
  EXPECT_FALSE(boxBelowBase(frame, {-5, -5, -5}, {1, 2.1, 5}));
  EXPECT_FALSE(boxBelowBase(frame, {-5, -5, -5}, {1, 2, 5})) << "touching the plane";
}

// ---- Culled hemicubes against the same ones drawing every element --------------------------

/// Expects two hemicubes' factors to be identical, bit for bit.
void expectSameFactors(const FormFactors& culled, const FormFactors& all, const std::string& where) {
  EXPECT_EQ(culled.elements, all.elements) << where;
  EXPECT_EQ(culled.factors, all.factors) << where;
  EXPECT_EQ(culled.sky, all.sky) << where;
  EXPECT_EQ(culled.backFaces, all.backFaces) << where;
}

/// A unit vector uniform on the sphere.
glm::dvec3 randomDirection(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  const double z = normal(rng), y = normal(rng), x = normal(rng);  // one draw each, in a fixed order
  return glm::normalize(glm::dvec3(x, y, z));
}

/// Triangles drawn over a series of hemicubes.
struct Drawn {
  size_t all = 0, culled = 0, hidden = 0;
};

/// Compares, from each point and normal, a hemicube culling hidden subtrees with one drawing
/// every element; returns the triangles drawn.
Drawn compareCulling(const HemicubeGeometry& g, double sceneSize, int R, const std::vector<std::pair<glm::dvec3, glm::dvec3>>& views) {
  Hemicube hidden(g, R, sceneSize), all(g, R, sceneSize);
  hidden.setCulling(HemicubeCulling::Hidden);
  all.setCulling(HemicubeCulling::None);
  FormFactors fh, fa;
  Drawn drawn;
  for (size_t k = 0; k < views.size(); ++k) {
    const auto& [x, n] = views[k];
    const double rotation = hemicubeRotation(5, k, 0);
    hidden.compute(x, n, rotation, fh);
    all.compute(x, n, rotation, fa);
    const std::string where = "view " + std::to_string(k) + " at (" + std::to_string(x.x) + ", " + std::to_string(x.y) +
                              ", " + std::to_string(x.z) + "), R = " + std::to_string(R);
    expectSameFactors(fh, fa, where + ", hidden subtrees culled");
    drawn.all += all.counts().drawn, drawn.culled += hidden.counts().drawn, drawn.hidden += hidden.counts().hidden;
  }
  return drawn;
}

/// Random points in box [lo, hi] with random normals.
std::vector<std::pair<glm::dvec3, glm::dvec3>> randomViews(const glm::dvec3& lo, const glm::dvec3& hi, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::pair<glm::dvec3, glm::dvec3>> views;
  for (int k = 0; k < count; ++k) {
    const glm::dvec3 direction = randomDirection(rng);  // one draw each, in a fixed order
    const double z = unit(rng), y = unit(rng), x = unit(rng);
    views.emplace_back(lo + glm::dvec3(x, y, z) * (hi - lo), direction);
  }
  return views;
}

TEST(HemicubeCullingTest, ARoomOfARowSeesTheSameAndDrawsFarLess) {
  // Five rooms in a row; the cube stands in the first, whose doorways show bits of the next.
  const test::RoomGrid grid{5, 1};
  const HemicubeGeometry g = test::roomGrid(grid);
  const double size = grid.room * 5;
  const double h = 0.5 * grid.wall + 0.01;
  const auto views = randomViews({h, 0.01, h}, {grid.room - h, grid.height - 0.01, grid.room - h}, 40, 3);
  for (int R : {32, 64}) {
    const Drawn drawn = compareCulling(g, size, R, views);
    std::printf("  R=%d: %zu elements, triangles drawn per hemicube %.0f of %.0f (all above the base)\n", R,
                g.elementCount(), double(drawn.culled) / views.size(), double(drawn.all) / views.size());
    // Only the first room and what the doorways show of the second and third are drawn.
    EXPECT_LT(double(drawn.culled), 0.5 * double(drawn.all)) << "R = " << R;
    EXPECT_GT(drawn.hidden, 0u);
  }
}

TEST(HemicubeCullingTest, RandomViewsInTheCornellBoxSeeTheSame) {
  const Scene scene = loadScene(kScenes + "cornell.json");
  const PatchMesh mesh = buildPatchMesh(scene, {30, 90});
  const HemicubeGeometry g = HemicubeGeometry::fromMesh(mesh);
  // Anywhere in the box (inside the blocks too), facing anywhere.
  const auto views = randomViews({1, 1, 1}, {555, 548, 558}, 60, 11);
  for (int R : {32, 64, 128}) compareCulling(g, scene.diagonal(), R, views);
}

TEST(HemicubeCullingTest, ShootersInTheCornellBoxSeeTheSame) {
  // As the solver shoots: from element centroids along their normals, their own excluded.
  const Scene scene = loadScene(kScenes + "cornell.json");
  const PatchMesh mesh = buildPatchMesh(scene, {30, 90});
  const HemicubeGeometry g = HemicubeGeometry::fromMesh(mesh);
  Hemicube hidden(g, 64, scene.diagonal()), all(g, 64, scene.diagonal());
  hidden.setCulling(HemicubeCulling::Hidden);
  all.setCulling(HemicubeCulling::None);
  FormFactors fh, fa;
  for (int e = 0; e < mesh.elementCount(); e += 53) {
    hidden.compute(mesh.centroid(e), mesh.normal(e), hemicubeRotation(2, e, 0), fh, {e});
    all.compute(mesh.centroid(e), mesh.normal(e), hemicubeRotation(2, e, 0), fa, {e});
    expectSameFactors(fh, fa, "element " + std::to_string(e));
  }
}

TEST(HemicubeCullingTest, AutoCullsInABuildingButNotInTheCornellBox) {
  // By default a cube culls where its probes find most elements hidden: in rooms, not in an
  // open box it sees almost whole.
  const Scene scene = loadScene(kScenes + "cornell.json");
  const PatchMesh mesh = buildPatchMesh(scene, {30, 90});
  const HemicubeGeometry box = HemicubeGeometry::fromMesh(mesh);
  const test::RoomGrid grid{4, 4};
  const HemicubeGeometry building = test::roomGrid(grid);
  FormFactors ff;
  Hemicube inBox(box, 32, scene.diagonal()), inBuilding(building, 32, 4 * grid.room);
  EXPECT_EQ(inBox.culling(), HemicubeCulling::Auto);
  inBox.compute(mesh.centroid(0), mesh.normal(0), 0.5, ff, {0});
  inBuilding.compute(grid.centre(1, 1, 1.0), {0, 1, 0}, 0.5, ff);
  EXPECT_EQ(inBox.culling(), HemicubeCulling::None);
  EXPECT_EQ(inBuilding.culling(), HemicubeCulling::Hidden);
  EXPECT_GT(inBuilding.counts().hidden, building.elementCount() / 2);
}

}  // namespace
}  // namespace rad
