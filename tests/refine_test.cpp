// Conforming refinement: longest-edge bisection keeps the mesh free of T-junctions, areas
// and element attributes; the T-junction check finds what it should.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/refine.h"
#include "mesh/scene/geometry.h"
#include "mesh/scene/readers/scene_loader.h"

namespace rad {
namespace {

const std::string kScenes = std::string(RAD_SOURCE_DIR) + "/scenes/";
/// Bisection halves areas exactly; geometry agrees to round-off.
constexpr double kAreaTolerance = 1e-9;

double smallestAngle(const PatchMesh& m) {
  double least = 180;
  for (int e = 0; e < m.elementCount(); ++e) {
    auto c = m.corners(e);
    least = std::min({least, angleDeg(c[0], c[1], c[2]), angleDeg(c[1], c[2], c[0]),
                      angleDeg(c[2], c[0], c[1])});
  }
  return least;
}

/// Every element listed, and those their propagation paths reach, bisected three times over;
/// the mesh stays conforming (within and across surfaces), each element keeps its base
/// element's attributes, areas add up, and angles stay above half the smallest before
/// (Rivara's bound). The contacts scene has contact lines across surfaces (a board resting on
/// the floor and the wall), where edges split on one surface are split inside another.
class RefineTest : public ::testing::TestWithParam<const char*> {};

TEST_P(RefineTest, BisectionConformsAndKeepsAreasAndAttributes) {
  Scene scene = loadScene(kScenes + GetParam());
  const double edge = scene.diagonal() / 20;
  PatchMesh m = buildPatchMesh(scene, {edge, 3 * edge, true, 1});
  const PatchMesh before = m;
  ASSERT_TRUE(findTJunctions(m, 1e-7, true).empty());
  const double angleBefore = smallestAngle(m);
  for (int round = 0; round < 3; ++round) {
    std::vector<int> some;
    for (int e = 0; e < m.elementCount(); e += 5) some.push_back(e);
    const int added = bisectElements(m, some);
    EXPECT_GE(added, int(some.size()));
  }
  EXPECT_TRUE(findTJunctions(m, 1e-7, true).empty());
  EXPECT_GE(smallestAngle(m), angleBefore / 2 - 1e-9);
  std::vector<double> patchArea(m.patches.size(), 0.0);
  for (int e = 0; e < m.elementCount(); ++e) {
    const int b = m.base(e);
    ASSERT_GE(b, 0);
    ASSERT_LT(b, before.elementCount());
    EXPECT_EQ(m.surface(e), before.surface(b));
    EXPECT_EQ(m.side(e), before.side(b));
    EXPECT_EQ(m.patch(e), before.patch(b));
    EXPECT_EQ(m.reflectance(e), before.reflectance(b));
    EXPECT_EQ(m.emission(e), before.emission(b));
    EXPECT_GT(glm::dot(m.normal(e), before.normal(b)), 1 - 1e-12);
    auto c = m.corners(e);
    EXPECT_NEAR(m.area(e) / triangleArea(c[0], c[1], c[2]), 1.0, kAreaTolerance);
    // The element lies inside its base element.
    auto p = before.corners(b);
    const glm::dvec3 centre = (c[0] + c[1] + c[2]) / 3.0, n = glm::cross(p[1] - p[0], p[2] - p[0]);
    for (int k = 0; k < 3; ++k)
      EXPECT_GE(glm::dot(glm::cross(p[(k + 1) % 3] - p[k], centre - p[k]), n), 0);
    patchArea[size_t(m.patch(e))] += m.area(e);
  }
  for (size_t p = 0; p < m.patches.size(); ++p) {
    EXPECT_NEAR(patchArea[p] / before.patches[p].area, 1.0, kAreaTolerance);
    for (int e : m.patches[p].elements) EXPECT_EQ(m.patch(e), int(p));
  }
  int listed = 0;
  for (const auto& p : m.patches) listed += int(p.elements.size());
  EXPECT_EQ(listed, m.elementCount());
}

INSTANTIATE_TEST_SUITE_P(Scenes, RefineTest, ::testing::Values("cornell.json", "contacts.json"));

/// A mesh of one surface from its points (x, y) and faces; their areas are not used here.
PatchMesh flatMesh(const std::vector<glm::dvec2>& points, const std::vector<std::array<int, 3>>& faces) {
  PatchMesh m;
  m.surfaces.resize(1);
  m.patches.resize(1);
  for (const auto& p : points) m.mesh.add_vertex({p.x, p.y, 0});
  for (const auto& f : faces) {
    auto h = m.mesh.add_face(TriMesh::VertexHandle(f[0]), TriMesh::VertexHandle(f[1]), TriMesh::VertexHandle(f[2]));
    m.setElement(h.idx(), 0, 0, 1.0, glm::dvec3(0.5), glm::dvec3(0.0), {0, 0, 1});
    m.setPatch(h.idx(), 0);
  }
  return m;
}

/// A unit square refined round after round towards its corner at the origin: no edge shorter
/// than the floor is split; without one, edges far shorter are.
TEST(RefineFloorTest, EdgesShorterThanTheFloorStayWhole) {
  constexpr double kFloor = 0.05;
  auto splitLengths = [](double floor) {
    PatchMesh m = flatMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 1, 2}, {0, 2, 3}});
    std::vector<double> lengths;
    for (int round = 0; round < 20; ++round) {
      std::vector<int> atOrigin;
      for (int e = 0; e < m.elementCount(); ++e)
        for (const auto& c : m.corners(e))
          if (c == glm::dvec3(0.0)) atOrigin.push_back(e);
      std::vector<EdgeSplit> splits;
      bisectElements(m, atOrigin, &splits, floor);
      for (const auto& s : splits)
        lengths.push_back((m.mesh.point(TriMesh::VertexHandle(s.from)) - m.mesh.point(TriMesh::VertexHandle(s.to))).norm());
    }
    return lengths;
  };
  const std::vector<double> floored = splitLengths(kFloor), unfloored = splitLengths(0);
  ASSERT_FALSE(floored.empty());
  EXPECT_GE(*std::min_element(floored.begin(), floored.end()), kFloor);
  EXPECT_LT(*std::min_element(unfloored.begin(), unfloored.end()), kFloor / 10);
}

/// A triangle beside a fan of flat slivers, their corners on its edge (as meshing left where a
/// cornice's end was cut to a line, micrometres apart), every element bisected round after
/// round without a floor: the slivers stay as they are and the rest is refined (halving them
/// made more without end, until the stack overflowed).
TEST(RefineFloorTest, FlatSliversStayWhole) {
  // The triangle (0, 1, 2) with its longest edge 0–1 outside; across its edge 1–2, slivers
  // whose corners lie on 1–2.
  PatchMesh m = flatMesh({{-3, 0.5}, {0, 0}, {0, 1}, {0, 0.5}, {0, 0.25}, {0, 1e-3}, {0, 1e-6}},
                         {{0, 1, 2}, {2, 1, 3}, {2, 3, 4}, {2, 4, 5}, {2, 5, 6}});
  auto flatElements = [&] {
    int flat = 0;
    for (int e = 0; e < m.elementCount(); ++e) {
      const auto c = m.corners(e);
      flat += triangleArea(c[0], c[1], c[2]) == 0;
    }
    return flat;
  };
  ASSERT_EQ(flatElements(), 4);
  for (int round = 0; round < 6; ++round) {
    std::vector<int> all(size_t(m.elementCount()));
    for (int e = 0; e < m.elementCount(); ++e) all[size_t(e)] = e;
    bisectElements(m, all);
  }
  EXPECT_EQ(flatElements(), 4);
  EXPECT_GT(m.elementCount(), 5 + 16);
}

/// Two triangles of one surface on either side of a line, one of them split at the line's
/// midpoint without the other: the midpoint is a T-junction. Split conformingly, none.
TEST(TJunctionTest, FindsTJunctions) {
  auto square = [](bool conforming) {
    PatchMesh m;
    m.surfaces.resize(1);
    auto v = [&](double x, double y) { return m.mesh.add_vertex({x, y, 0}); };
    auto a = v(0, 0), b = v(2, 0), c = v(2, 2), d = v(0, 2), mid = v(1, 1);
    std::vector<std::array<TriMesh::VertexHandle, 3>> faces;
    if (conforming) faces = {{a, b, mid}, {b, c, mid}, {c, d, mid}, {d, a, mid}};
    else faces = {{a, b, c}, {c, d, mid}, {d, a, mid}};  // mid lies inside edge a–c
    for (const auto& f : faces) {
      auto h = m.mesh.add_face(f[0], f[1], f[2]);
      m.setElement(h.idx(), 0, 0, 1.0, glm::dvec3(0.5), glm::dvec3(0.0), {0, 0, 1});
      m.setPatch(h.idx(), 0);
    }
    return m;
  };
  auto found = findTJunctions(square(false));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].vertex, 4);
  EXPECT_TRUE(findTJunctions(square(true)).empty());
}

}  // namespace
}  // namespace rad
