// The default camera of a scene without one (mesh/results/default_camera.h): into an open box through
// its open side, inside a closed room at eye height, around an object; and the rays it is chosen
// by (mesh/surface_rays.h).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "mesh/results/default_camera.h"
#include "mesh/results/result_file.h"
#include "mesh/scene/camera.h"
#include "mesh/scene/readers/scene_loader.h"
#include "mesh/surface_rays.h"
#include "tests/support.h"

namespace rad {
namespace {

/// Round-off on positions of a few thousand units.
constexpr double kPosition = 1e-9;
/// How far from +y or from its axis a view direction may be: a tenth of a degree.
constexpr double kDirection = 1.7e-3;
/// How far (mm) the centre of a result's lamp elements, stored as float, may be from the lamp's.
constexpr double kLampCentre = 1.0;
/// How far from x = 0 (m) McGuire's boxes have their axis: their walls are a few cm off square.
constexpr double kMcGuireAxis = 0.05;

/// The unit view direction of a camera.
glm::dvec3 viewOf(const Camera& c) { return glm::normalize(c.target - c.eye); }

/// Whether p lies inside the box [lo, hi].
bool inside(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi) {
  return p.x > lo.x && p.y > lo.y && p.z > lo.z && p.x < hi.x && p.y < hi.y && p.z < hi.z;
}

/// The scene with every polygon turned to face the other way.
Scene turnedInsideOut(Scene scene) {
  for (Surface& surface : scene.surfaces)
    for (Polygon& polygon : surface.polygons) std::reverse(polygon.outer.begin(), polygon.outer.end());
  return scene;
}

/*  A 2 x 2 square at z = 0 facing +z, with a 1 x 1 hole in its middle:
        +-------+
        |  +-+  |      rays along -z at (0.5, 0.5) meet the front, at (1, 1) go through the hole
        |  +-+  |
        +-------+                                                                               */
std::vector<Polygon> squareWithHole() {
  Polygon square{{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, {{{0.5, 0.5, 0}, {1.5, 0.5, 0}, {1.5, 1.5, 0}, {0.5, 1.5, 0}}}};
  return {square};
}

TEST(SurfaceRaysTest, MeetsTheFrontAndTheBackAndPassesTheHole) {
  const std::vector<Polygon> polygons = squareWithHole();
  const SurfaceRays rays(polygons, {false});
  const auto front = rays.firstHit({0.25, 0.25, 3}, {0, 0, -1}, false);
  ASSERT_TRUE(front);
  EXPECT_TRUE(front->front);
  EXPECT_NEAR(front->t, 3, kPosition);
  EXPECT_FALSE(rays.firstHit({1, 1, 3}, {0, 0, -1}, false)) << "through the hole";
  const auto back = rays.firstHit({0.25, 0.25, -2}, {0, 0, 1}, false);
  ASSERT_TRUE(back);
  EXPECT_FALSE(back->front);
  EXPECT_FALSE(rays.firstHit({0.25, 0.25, -2}, {0, 0, 1}, true)) << "a back is passed";
  EXPECT_FALSE(rays.firstHit({0.25, 0.25, 3}, {0, 0, 1}, false)) << "behind the ray";
}

TEST(SurfaceRaysTest, ATwoSidedPolygonIsMetFromBothSides) {
  const std::vector<Polygon> polygons = squareWithHole();
  const SurfaceRays rays(polygons, {true});
  const auto back = rays.firstHit({0.25, 0.25, -2}, {0, 0, 1}, true);
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->front);
}

TEST(SurfaceRaysTest, OfPolygonsMetAtOneDistanceTheFirstGivenWins) {
  Polygon up = squareWithHole()[0], down = up;
  std::reverse(down.outer.begin(), down.outer.end());
  const std::vector<Polygon> upFirst{up, down}, downFirst{down, up};
  const auto a = SurfaceRays(upFirst, {false, false}).firstHit({0.25, 0.25, 3}, {0, 0, -1}, false);
  const auto b = SurfaceRays(downFirst, {false, false}).firstHit({0.25, 0.25, 3}, {0, 0, -1}, false);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->polygon, 0);
  EXPECT_TRUE(a->front);
  EXPECT_EQ(b->polygon, 0);
  EXPECT_FALSE(b->front);
}

/// An 8 × 8 grid of 0.5 × 0.5 squares at z = 0 facing +z, one per unit square, square i·8 + j
/// at (i, j): enough for Embree to cull boxes.
std::vector<Polygon> gridOfSquares() {
  std::vector<Polygon> squares;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      squares.push_back({{{i, j, 0}, {i + 0.5, j, 0}, {i + 0.5, j + 0.5, 0}, {i, j + 0.5, 0}}, {}});
  return squares;
}

TEST(SurfaceRaysTest, MeetsFromFarAwayAndNothingInAnEmptyList) {
  // From 1e9 away a float origin is off by tens of units: the ray must not lose the squares.
  const std::vector<Polygon> squares = gridOfSquares();
  const SurfaceRays rays(squares, std::vector<bool>(squares.size(), false));
  for (int k = 0; k < 64; ++k) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(1 + k % 3, 2 + k % 5, 3)), p(k / 8 + 0.25, k % 8 + 0.25, 0);
    const auto hit = rays.firstHit(p + 1e9 * n, -n, false);
    ASSERT_TRUE(hit) << "square " << k;
    EXPECT_EQ(hit->polygon, k);
    EXPECT_NEAR(hit->t, 1e9, 1e9 * kPosition);
  }
  EXPECT_FALSE(SurfaceRays({}, {}).firstHit({0, 0, 0}, {0, 0, 1}, false));
}

TEST(DefaultCameraTest, UnitsPerMetre) {
  EXPECT_EQ(unitsPerMetre("mm"), 1000.0);
  EXPECT_EQ(unitsPerMetre("Metres"), 1.0);
  EXPECT_NEAR(*unitsPerMetre("ft"), 3.28084, 1e-5);
  EXPECT_FALSE(unitsPerMetre(""));
  EXPECT_FALSE(unitsPerMetre("furlongs"));
}

// The Cornell box is open at z = 0: the eye stands in front of it on the axis through the box's
// centre, where the opening (556 x 548.8 at most) fills a 45° view, looking +z.
TEST(DefaultCameraTest, CornellBoxIsSeenThroughItsOpenFront) {
  const Scene scene = loadScene(test::kScenes + "cornell.json");
  const Camera c = defaultCamera(scene);
  EXPECT_GT(glm::dot(viewOf(c), glm::dvec3(0, 0, 1)), 1 - kDirection) << "view " << viewOf(c).z;
  const double halfOpening = 556.0 / 2;
  EXPECT_NEAR(c.eye.z, -halfOpening / std::tan(glm::radians(c.fovYDeg / 2)), kPosition);
  EXPECT_NEAR(c.eye.x, 278, kPosition);
  EXPECT_NEAR(c.eye.y, 548.8 / 2, kPosition);
  checkCamera(c, "default camera");
}

// McGuire's boxes (metres, no camera, one-line scenes) are open at +z: looking -z into them from
// outside, on their axis.
TEST(DefaultCameraTest, McGuireCornellBoxesAreSeenThroughTheirOpenSide) {
  for (const std::string& path : {test::kScenes + "cornell_original.json", test::kData + "mcguire/cornell_water.json"}) {
    const Camera c = defaultCamera(loadScene(path));
    EXPECT_GT(glm::dot(viewOf(c), glm::dvec3(0, 0, -1)), 1 - kDirection) << path << ": view " << viewOf(c).z;
    EXPECT_GT(c.eye.z, 0.99) << path << ": outside the open side";
    EXPECT_LT(std::abs(c.eye.x), kMcGuireAxis) << path;
  }
}

// Two rooms, 2500 mm high, behind a partition with a doorway, the lamp in the front room: the
// eye stands in open air at 1.6 m, looking horizontally at the lamp.
TEST(DefaultCameraTest, ClosedBuildingIsSeenFromInsideAtEyeHeight) {
  const Scene scene = loadScene(test::kScenes + "doorway.json");
  const Camera c = defaultCamera(scene);
  EXPECT_NEAR(c.eye.y, 1600, kPosition);
  EXPECT_NEAR(c.target.y, c.eye.y, kPosition) << "horizontal";
  EXPECT_TRUE(inside(c.eye, {0, 0, 0}, {4000, 2500, 8100})) << c.eye.x << " " << c.eye.z;
  EXPECT_FALSE(c.eye.z >= 4000 && c.eye.z <= 4100 && (c.eye.x <= 1600 || c.eye.x >= 2500)) << "in the wall";
  const glm::dvec3 lamp(2000, 1600, 1500);
  EXPECT_GT(glm::dot(viewOf(c), glm::normalize(lamp - c.eye)), 1 - kDirection) << "towards the lamp";
}

// The 1 m closed cube, faces inwards, its whole ceiling a lamp: the eye inside at 0.8 of its
// height (below 1.6 m), looking horizontally (the lamp is overhead).
TEST(DefaultCameraTest, LowClosedRoomKeepsTheEyeBelowItsCeiling) {
  const Camera c = defaultCamera(loadScene(test::kScenes + "cube.json"));
  EXPECT_NEAR(c.eye.y, 0.8, kPosition);
  EXPECT_NEAR(c.target.y, c.eye.y, kPosition);
  EXPECT_TRUE(inside(c.eye, {0, 0, 0}, {1, 1, 1}));
}

// Without units the eye is at 0.6 of the room's height.
TEST(DefaultCameraTest, RoomWithoutUnitsTakesSixTenthsOfItsHeight) {
  Scene scene = loadScene(test::kScenes + "cube.json");
  scene.units.clear();
  EXPECT_NEAR(defaultCamera(scene).eye.y, 0.6, kPosition);
}

/*  A closed 4 x 2.5 x 4 m room (faces inwards) with a 2 x 2 m table top at 0.75 m in its middle,
    seen from above:
        +-----------+
        |   +---+   |    the middle of the floor plan is over the table: the eye stands
        |   | T |   |    beside it, 1.6 m above the floor (not above the table top)
        |   +---+   |
        +-----------+                                                                        */
TEST(DefaultCameraTest, EyeStandsOnTheFloorBesideTheTable) {
  const Scene scene = parseScene(R"({"version": 1, "units": "m",
      "materials": {"w": {"reflectance": [0.5, 0.5, 0.5]}},
      "surfaces": [
        {"name": "floor", "material": "w", "polygon": [[0,0,0],[0,0,4],[4,0,4],[4,0,0]]},
        {"name": "ceiling", "material": "w", "polygon": [[0,2.5,0],[4,2.5,0],[4,2.5,4],[0,2.5,4]]},
        {"name": "x0", "material": "w", "polygon": [[0,0,0],[0,2.5,0],[0,2.5,4],[0,0,4]]},
        {"name": "x1", "material": "w", "polygon": [[4,0,0],[4,0,4],[4,2.5,4],[4,2.5,0]]},
        {"name": "z0", "material": "w", "polygon": [[0,0,0],[4,0,0],[4,2.5,0],[0,2.5,0]]},
        {"name": "z1", "material": "w", "polygon": [[0,0,4],[0,2.5,4],[4,2.5,4],[4,0,4]]},
        {"name": "table", "material": "w", "polygon": [[1,0.75,1],[1,0.75,3],[3,0.75,3],[3,0.75,1]]}]})",
                                 "table.json", test::kData);
  const Camera c = defaultCamera(scene);
  EXPECT_NEAR(c.eye.y, 1.6, kPosition);
  EXPECT_TRUE(inside(c.eye, {0, 0, 0}, {4, 2.5, 4}));
  EXPECT_FALSE(c.eye.x > 1 && c.eye.x < 3 && c.eye.z > 1 && c.eye.z < 3) << c.eye.x << " " << c.eye.z;
}

// The same cube turned inside out is a block: framed from the raised diagonal (1, 0.6, 1), its
// bounding sphere filling the view.
TEST(DefaultCameraTest, ClosedBlockIsFramedFromOutside) {
  const Camera c = defaultCamera(turnedInsideOut(loadScene(test::kScenes + "cube.json")));
  const glm::dvec3 centre(0.5);
  EXPECT_NEAR(glm::length(c.target - centre), 0, kPosition);
  EXPECT_GT(glm::dot(glm::normalize(c.eye - centre), glm::normalize(glm::dvec3(1, 0.6, 1))), 1 - kDirection);
  EXPECT_NEAR(glm::length(c.eye - centre), std::sqrt(3.0) / 2 / std::sin(glm::radians(c.fovYDeg / 2)), kPosition);
}

// A box on a floor under a lamp (tests/data/box_on_floor.json) is an object too.
TEST(DefaultCameraTest, BoxOnAFloorIsFramedFromOutside) {
  const Camera c = defaultCamera(loadScene(test::kData + "box_on_floor.json"));
  EXPECT_GT(glm::dot(-viewOf(c), glm::normalize(glm::dvec3(1, 0.6, 1))), 1 - kDirection);
}

// radview's fallback for a result without a camera: the result's triangles give the open box
// view (the coarse Cornell result of tests/data, turned half a turn to open at +z).
TEST(DefaultCameraTest, ResultWithoutCameraIsSeenThroughItsOpenSide) {
  ResultFile result = readResultFile(test::kData + "cornell_coarse_result.ply");
  result.camera.reset();
  for (glm::vec3& p : result.positions) p.x = -p.x, p.z = -p.z;
  const Camera c = defaultCamera(result);
  EXPECT_GT(glm::dot(viewOf(c), glm::dvec3(0, 0, -1)), 1 - kDirection);
  EXPECT_GT(c.eye.z, 0);
  result.faces.clear();
  EXPECT_EQ(defaultCamera(result).eye, defaultCamera(result.boundsMin, result.boundsMax).eye) << "bounds only";
}

// The main light is the Cornell lamp (213..343 x 227..332 at y = 548.8), in the scene and, as
// its brightest faces, in the solved result.
TEST(DefaultCameraTest, MainLightIsTheLamp) {
  const glm::dvec3 lamp(278, 548.8, 279.5);
  const auto fromScene = viewGeometry(loadScene(test::kScenes + "cornell.json")).light;
  ASSERT_TRUE(fromScene);
  EXPECT_NEAR(glm::length(*fromScene - lamp), 0, kPosition);
  const auto fromResult = viewGeometry(readResultFile(test::kData + "cornell_coarse_result.ply")).light;
  ASSERT_TRUE(fromResult);
  EXPECT_LT(glm::length(*fromResult - lamp), kLampCentre) << fromResult->x << " " << fromResult->z;
}

}  // namespace
}  // namespace rad
