// The patch mesh: areas, normals, edge lengths, shapes and shared boundary points.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/polygon_mesher.h"
#include "mesh/scene/geometry.h"
#include "mesh/scene/readers/scene_loader.h"
#include "tests/support.h"

namespace rad {
namespace {

using test::kScenes;

/// Surface areas within this of the reference table (cornell_box.md).
constexpr double kCornellAreaTolerance = 5e-4;
/// The area cut away under a block against its footprint (the issue asks for 0.1 %).
constexpr double kCutAreaTolerance = 1e-3;
/// Meshing may not change the area beyond round-off.
constexpr double kAreaPreservation = 1e-9;
/// Smallest element angle wherever the input polygon's angles allow.
constexpr double kMinAngleDeg = 15;

PatchMesh meshScene(const Scene& scene, double element, double patch) {
  return buildPatchMesh(scene, MeshSettings{element, patch});
}

/// Meshed area per surface (one side), plus what contacts cut away when `withCut`.
std::vector<double> surfaceAreas(const PatchMesh& m, size_t surfaces, bool withCut = true) {
  std::vector<double> area(surfaces, 0.0);
  for (int e = 0; e < m.elementCount(); ++e)
    if (m.side(e) == 0) area[m.surface(e)] += m.area(e);
  if (withCut)
    for (const auto& c : m.cutAway) area[c.surface] += c.area;
  return area;
}

class CornellTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(loadScene(kScenes + "cornell.json"));
    mesh_ = new PatchMesh(meshScene(*scene_, 30, 90));
  }
  static void TearDownTestSuite() {
    delete mesh_;
    delete scene_;
  }
  int surfaceIndex(const std::string& name) const {
    for (size_t s = 0; s < scene_->surfaces.size(); ++s)
      if (scene_->surfaces[s].name == name) return int(s);
    ADD_FAILURE() << "no surface " << name;
    return -1;
  }
  static Scene* scene_;
  static PatchMesh* mesh_;
};
Scene* CornellTest::scene_ = nullptr;
PatchMesh* CornellTest::mesh_ = nullptr;

TEST_F(CornellTest, SurfaceAreasMatchTheReferenceTable) {
  const std::map<std::string, double> reference = {
      {"floor", 308231.0},          {"ceiling", 297265.2},        {"light", 13650.0},
      {"back_wall", 303376.6},      {"right_wall", 306889.0},     {"left_wall", 306902.0},
      {"short_block_top", 27633.0}, {"short_block_side_1", 27344}, {"short_block_side_2", 27610},
      {"short_block_side_3", 27562}, {"short_block_side_4", 27199}, {"tall_block_top", 27626.5},
      {"tall_block_side_1", 54905}, {"tall_block_side_2", 54689},  {"tall_block_side_3", 55221},
      {"tall_block_side_4", 54590}};
  auto area = surfaceAreas(*mesh_, scene_->surfaces.size());
  ASSERT_EQ(reference.size(), scene_->surfaces.size());
  for (const auto& [name, expected] : reference) {
    int s = surfaceIndex(name);
    EXPECT_NEAR(area[s] / expected, 1.0, kCornellAreaTolerance) << name << ": " << area[s];
  }
}

/// The floor under each block is enclosed by the block's sides: it is cut away, exactly the
/// block's footprint (its top, as the sides are vertical), and nothing else is.
TEST_F(CornellTest, FloorUnderTheBlocksIsCutAway) {
  int floor = surfaceIndex("floor");
  ASSERT_EQ(mesh_->cutAway.size(), 2u);
  std::map<std::string, double> footprint = {{"short", 27633.0}, {"tall", 27626.5}};
  for (const auto& c : mesh_->cutAway) {
    EXPECT_EQ(c.surface, floor);
    ASSERT_EQ(c.enclosedBy.size(), 4u);
    std::string block = scene_->surfaces[c.enclosedBy[0]].name.substr(0, 4) == "tall" ? "tall" : "short";
    for (int s : c.enclosedBy) EXPECT_EQ(scene_->surfaces[s].name.rfind(block + "_block_side_", 0), 0u);
    EXPECT_NEAR(c.area / footprint[block], 1.0, kCutAreaTolerance) << block;
    footprint.erase(block);
  }
  EXPECT_TRUE(footprint.empty());
  EXPECT_NEAR(surfaceAreas(*mesh_, scene_->surfaces.size(), false)[floor] / (308231.0 - 27633.0 - 27626.5),
              1.0, kCutAreaTolerance);
  // No floor element lies under a block (centroids tested against the footprints' inside).
  for (int e = 0; e < mesh_->elementCount(); ++e) {
    if (mesh_->surface(e) != floor) continue;
    glm::dvec3 c = mesh_->centroid(e);
    for (const char* top : {"short_block_top", "tall_block_top"}) {
      const auto& q = scene_->surfaces[surfaceIndex(top)].polygons[0].outer;
      bool inside = true;
      for (size_t k = 0; k < q.size(); ++k) {
        glm::dvec3 a = q[k], b = q[(k + 1) % q.size()];
        double side = (b.x - a.x) * (c.z - a.z) - (b.z - a.z) * (c.x - a.x);
        inside = inside && side < 0;  // −(y of (b − a)×(c − a)): the tops face +y
      }
      EXPECT_FALSE(inside) << "floor element under " << top << " at " << c.x << " " << c.z;
    }
  }
}

TEST_F(CornellTest, CeilingHasAHoleWhereTheLightIs) {
  int ceiling = surfaceIndex("ceiling");
  EXPECT_NEAR(surfaceAreas(*mesh_, scene_->surfaces.size(), false)[ceiling] / 297265.2, 1.0,
              kCornellAreaTolerance);
  for (int e = 0; e < mesh_->elementCount(); ++e) {
    if (mesh_->surface(e) != ceiling) continue;
    glm::dvec3 c = mesh_->centroid(e);
    bool underLight = c.x > 213 && c.x < 343 && c.z > 227 && c.z < 332;
    EXPECT_FALSE(underLight) << "ceiling element at " << c.x << " " << c.z;
  }
}

TEST_F(CornellTest, NormalsPointIntoTheBoxAndOutOfTheBlocks) {
  const glm::dvec3 boxCentre(278, 274.4, 279.6);
  const glm::dvec3 shortCentre(186, 82.5, 168.5), tallCentre(368.5, 165, 351.5);
  for (int e = 0; e < mesh_->elementCount(); ++e) {
    const std::string& name = scene_->surfaces[mesh_->surface(e)].name;
    glm::dvec3 c = mesh_->centroid(e), n = mesh_->normal(e);
    if (name.rfind("short_block", 0) == 0)
      EXPECT_GT(glm::dot(n, c - shortCentre), 0) << name;
    else if (name.rfind("tall_block", 0) == 0)
      EXPECT_GT(glm::dot(n, c - tallCentre), 0) << name;
    else
      EXPECT_GT(glm::dot(n, boxCentre - c), 0) << name;
    // The stored normal is the geometric one of the counter-clockwise corners.
    auto k = mesh_->corners(e);
    EXPECT_NEAR(glm::dot(glm::normalize(glm::cross(k[1] - k[0], k[2] - k[0])), n), 1.0, 1e-6)
        << name;
  }
  int light = surfaceIndex("light");
  for (int e = 0; e < mesh_->elementCount(); ++e)
    if (mesh_->surface(e) == light) {
      EXPECT_NEAR(mesh_->normal(e).y, -1.0, 1e-12);
    }
}

TEST_F(CornellTest, NonPlanarRedWallIsTriangulatedAndSaysSo) {
  bool warned = false;
  for (const auto& w : mesh_->warnings) warned = warned || w.find("left_wall") != std::string::npos;
  EXPECT_TRUE(warned);
  int red = surfaceIndex("left_wall");
  std::set<std::pair<long, long>> normals;  // two planar halves: two distinct normals
  for (int e = 0; e < mesh_->elementCount(); ++e)
    if (mesh_->surface(e) == red)
      normals.insert({std::lround(mesh_->normal(e).x * 1e6), std::lround(mesh_->normal(e).z * 1e6)});
  EXPECT_EQ(normals.size(), 2u);
}

/// Every vertex on an edge where two surfaces meet has a twin at the same position in the
/// other surface, so a rasteriser sees no crack between them.
TEST_F(CornellTest, VerticesOnSharedEdgesHaveTwins) {
  const TriMesh& m = mesh_->mesh;
  struct Edge {
    glm::dvec3 a, b;
  };
  size_t n = scene_->surfaces.size();
  std::vector<std::vector<Edge>> edges(n);
  std::vector<std::set<std::array<double, 3>>> points(n);
  std::vector<std::vector<glm::dvec3>> boundaryPoints(n);
  for (auto h : m.halfedges()) {
    if (!m.is_boundary(h)) continue;
    int s = mesh_->surface(m.face_handle(m.opposite_halfedge_handle(h)).idx());
    glm::dvec3 a = PatchMesh::toGlm(m.point(m.from_vertex_handle(h)));
    glm::dvec3 b = PatchMesh::toGlm(m.point(m.to_vertex_handle(h)));
    edges[s].push_back({a, b});
    boundaryPoints[s].push_back(a);
    points[s].insert({a.x, a.y, a.z});
  }
  const double tolerance = 1e-9 * scene_->diagonal();
  int shared = 0;
  for (size_t s = 0; s < n; ++s)
    for (const auto& p : boundaryPoints[s])
      for (size_t t = 0; t < n; ++t) {
        if (t == s) continue;
        for (const auto& e : edges[t]) {
          glm::dvec3 d = e.b - e.a;
          double u = glm::dot(p - e.a, d) / glm::dot(d, d);
          if (u < 0 || u > 1 || glm::length(e.a + d * u - p) > tolerance) continue;
          ++shared;
          EXPECT_TRUE(points[t].count({p.x, p.y, p.z}))
              << scene_->surfaces[s].name << " point (" << p.x << ", " << p.y << ", " << p.z
              << ") lies on an edge of " << scene_->surfaces[t].name << " without a twin";
        }
      }
  EXPECT_GT(shared, 1000);  // the walls, floor, ceiling, light and block tops do meet
}

TEST_F(CornellTest, EdgesAnglesAndPatchesRespectTheSettings) {
  EXPECT_LE(mesh_->stats.maxEdge, 30 * (1 + 1e-12));
  EXPECT_LE(mesh_->stats.maxPatchDiameter, 90 * (1 + 1e-12));
  EXPECT_GE(mesh_->stats.minAngleDeg, kMinAngleDeg);
  for (const auto& p : mesh_->patches) {
    double area = 0;
    for (int e : p.elements) {
      EXPECT_EQ(mesh_->patch(e), &p - &mesh_->patches[0]);
      EXPECT_EQ(mesh_->surface(e), p.surface);
      area += mesh_->area(e);
      for (const auto& c : mesh_->corners(e))
        EXPECT_LE(glm::length(c - p.centroid), p.diameter * (1 + 1e-9));
    }
    EXPECT_NEAR(area / p.area, 1.0, 1e-12);
  }
}

/// The area of every planar polygon is kept to round-off.
/// Contact lines that cross each other inside a face (interpenetrating parts of a downloaded
/// model, a lamp pierced by a finely tessellated holder) are the contacts' doing: the face is
/// meshed without them, a scene polygon or a mesh file's face alike. A ring that crosses
/// itself is the user's, and refused, naming the polygon.
TEST(MeshingTest, CrossingLinesAreLeftOutCrossingRingsRefused) {
  Polygon2 p;
  p.rings = {{{0, 0}, {10, 0}, {10, 10}, {0, 10}}};
  p.ids = {{0, 1, 2, 3}};
  p.lines = {{{2, 2}, {8, 8}}, {{2, 8}, {8, 2}}};
  p.lineIds = {{-1, -1}, {-1, -1}};
  for (bool meshFace : {false, true}) {
    const Triangulation2 t = meshPolygon(p, 3, "crossing", meshFace);
    double area = 0;
    for (const auto& tri : t.triangles) {
      const glm::dvec2 a = t.points[size_t(tri[0])], b = t.points[size_t(tri[1])], c = t.points[size_t(tri[2])];
      area += 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    }
    EXPECT_NEAR(area, 100, 1e-9) << meshFace;
  }
  Polygon2 bowTie;
  bowTie.rings = {{{0, 0}, {10, 10}, {10, 0}, {0, 10}}};
  bowTie.ids = {{0, 1, 2, 3}};
  test::expectError([&] { meshPolygon(bowTie, 3, "bow tie", false); }, {"bow tie", "edges that cross each other"});
}

TEST(MeshingTest, AreaIsPreserved) {
  for (const char* name : {"cornell.json", "cornell_empty.json", "furnace.json", "cube.json",
                           "parallel_squares.json"}) {
    Scene scene = loadScene(kScenes + name);
    double L = scene.diagonal() / 17;
    PatchMesh m = meshScene(scene, L, 3 * L);
    auto area = surfaceAreas(m, scene.surfaces.size());
    for (size_t s = 0; s < scene.surfaces.size(); ++s) {
      const Polygon& p = scene.surfaces[s].polygons[0];
      double expected = polygonArea(p);
      if (scene.surfaces[s].name == "left_wall") {
        // Non-planar: the area of its two planar triangles, whichever diagonal was cut.
        const auto& q = p.outer;
        double d02 = triangleArea(q[0], q[1], q[2]) + triangleArea(q[0], q[2], q[3]);
        double d13 = triangleArea(q[1], q[2], q[3]) + triangleArea(q[1], q[3], q[0]);
        expected = std::abs(area[s] - d02) < std::abs(area[s] - d13) ? d02 : d13;
      }
      EXPECT_NEAR(area[s] / expected, 1.0, kAreaPreservation) << name << " " << s;
    }
  }
}

TEST(MeshingTest, ElementCountScalesWithAreaOverEdgeSquared) {
  Scene scene = loadScene(kScenes + "cornell_empty.json");
  int coarse = meshScene(scene, 40, 120).elementCount();
  int fine = meshScene(scene, 20, 120).elementCount();
  double ratio = double(fine) / coarse;
  EXPECT_GT(ratio, 3.0) << coarse << " -> " << fine;
  EXPECT_LT(ratio, 5.0) << coarse << " -> " << fine;
  // And the count is of the order of area / L^2 (equilateral triangles of edge L/2 to L).
  double area = 0;
  for (const auto& s : scene.surfaces) area += polygonArea(s.polygons[0]);
  double perTriangle = std::sqrt(3.0) / 4 * 20 * 20;
  EXPECT_GT(fine, area / perTriangle);
  EXPECT_LT(fine, 4 * area / perTriangle * 1.5);
}

TEST(MeshingTest, IsDeterministic) {
  Scene scene = loadScene(kScenes + "cornell.json");
  PatchMesh a = meshScene(scene, 45, 90), b = meshScene(scene, 45, 90);
  ASSERT_EQ(a.elementCount(), b.elementCount());
  for (int e = 0; e < a.elementCount(); ++e) {
    auto ca = a.corners(e), cb = b.corners(e);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(ca[k], cb[k]);
  }
}

TEST(MeshingTest, TwoSidedSurfaceGetsAnOppositeCopy) {
  Scene scene = parseScene(R"({"version": 1,
    "materials": {"m": {"reflectance": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
    "surfaces": [{"name": "panel", "material": "m", "two_sided": true,
                  "polygon": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}]})",
                           "panel.json", ".");
  PatchMesh m = meshScene(scene, 0.25, 0.5);
  int front = 0, back = 0;
  for (int e = 0; e < m.elementCount(); ++e) {
    glm::dvec3 n = m.normal(e);
    if (m.side(e) == 0) {
      ++front;
      EXPECT_NEAR(n.z, 1.0, 1e-12);
    } else {
      ++back;
      EXPECT_NEAR(n.z, -1.0, 1e-12);
    }
  }
  EXPECT_EQ(front, back);
  EXPECT_GT(front, 0);
  // Each side has its own vertices: no vertex is used by both sides.
  for (auto v : m.mesh.vertices()) {
    std::set<int> sides;
    for (auto f : m.mesh.vf_range(v)) sides.insert(m.side(f.idx()));
    EXPECT_EQ(sides.size(), 1u);
  }
  EXPECT_NEAR(m.surfaces[0].area, 1.0, 1e-12);
}

TEST(GeometryTest, ConvexHullKeepsTheCornersCounterClockwise) {
  // A square with points on its edges and inside: its four corners, counter-clockwise.
  const std::vector<glm::dvec2> points = {{0, 0}, {0.5, 0}, {1, 0}, {0.3, 0.4}, {1, 1}, {0, 1}, {0, 0.5}, {0.5, 1}};
  const std::vector<size_t> hull = convexHull(points);
  ASSERT_EQ(hull.size(), 4u);
  for (size_t k : hull) EXPECT_TRUE(k == 0 || k == 2 || k == 4 || k == 5) << k;
  double twiceArea = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 &a = points[hull[i]], &b = points[hull[(i + 1) % hull.size()]];
    twiceArea += a.x * b.y - a.y * b.x;
  }
  EXPECT_DOUBLE_EQ(twiceArea, 2.0);  // positive: counter-clockwise, and the square's area
  // Collinear points leave the two ends; fewer than three points are kept as they are.
  EXPECT_EQ(convexHull({{0, 0}, {1, 1}, {2, 2}}).size(), 2u);
  EXPECT_EQ(convexHull({{0, 0}, {1, 1}}).size(), 2u);
}

}  // namespace
}  // namespace rad
