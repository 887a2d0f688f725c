// Contact lines: the floor next to the Cornell box's blocks against the exact direct light, and
// the contacts scene (a box half sunk into the floor, a board leaning against a wall).
#include <cmath>
#include <cstdio>
#include <map>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/adaptive.h"
#include "radiosity/result.h"
#include "radiosity/settings.h"
#include "radiosity/shooting/progressive_solver.h"
#include "radiosity/solve.h"

namespace rad {
namespace {

const std::string kScenes = std::string(RAD_SOURCE_DIR) + "/scenes/";

/// The bound for the floor 4 mm from a block's base.
constexpr double kNearBaseTolerance = 0.05;
/// Light cells per side for the exact visible factor (midpoint rule; converged to ~1e-4).
constexpr int kLightCells = 160;

/// Ray (origin o, direction d) hits triangle (a, b, c) at a parameter in (0, 1)
/// (Möller–Trumbore).
bool hits(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
          const glm::dvec3& c) {
  glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return false;
  glm::dvec3 s = o - a;
  double u = glm::dot(s, p) / det;
  if (u < 0 || u > 1) return false;
  glm::dvec3 q = glm::cross(s, e1);
  double v = glm::dot(d, q) / det;
  if (v < 0 || u + v > 1) return false;
  double t = glm::dot(e2, q) / det;
  return t > 1e-9 && t < 1 - 1e-9;
}

/// The form factor from floor point x (normal +y) to the light, blocks occluding: the
/// light cut into kLightCells² cells, each seen (or not) from its centre.
double visibleLightFactor(const Scene& scene, const glm::dvec3& x, bool occluded = true) {
  const Ring* light = nullptr;
  std::vector<const Ring*> occluders;
  for (const auto& s : scene.surfaces) {
    if (s.name == "light") light = &s.polygons[0].outer;
    if (occluded && s.name.find("_block_") != std::string::npos)
      occluders.push_back(&s.polygons[0].outer);
  }
  const Ring& q = *light;
  const glm::dvec3 n(0, 1, 0), lightNormal(0, -1, 0);
  double F = 0;
  for (int i = 0; i < kLightCells; ++i)
    for (int j = 0; j < kLightCells; ++j) {
      double u = (i + 0.5) / kLightCells, v = (j + 0.5) / kLightCells;
      glm::dvec3 y = q[0] + (q[1] - q[0]) * u + (q[3] - q[0]) * v;
      double cellArea = glm::length(glm::cross(q[1] - q[0], q[3] - q[0])) / (kLightCells * kLightCells);
      glm::dvec3 d = y - x;
      double r2 = glm::dot(d, d);
      double cosX = glm::dot(n, d) / std::sqrt(r2), cosY = glm::dot(lightNormal, -d) / std::sqrt(r2);
      if (cosX <= 0 || cosY <= 0) continue;
      bool blocked = false;
      for (const Ring* o : occluders)
        for (size_t k = 1; k + 1 < o->size() && !blocked; ++k)
          blocked = hits(x, d, (*o)[0], (*o)[k], (*o)[k + 1]);
      if (!blocked) F += cosX * cosY / (M_PI * r2) * cellArea;
    }
  return F;
}

/// Gouraud value of the floor at x (what the viewer draws), green channel.
double floorValue(const PatchMesh& mesh, int floor, const std::vector<glm::dvec3>& vertexB,
                  const glm::dvec3& x) {
  std::vector<int> elements;
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (mesh.surface(e) == floor) elements.push_back(e);
  const auto value = gouraudAt(mesh, elements, vertexB, x);
  if (!value) ADD_FAILURE() << "no floor element at " << x.x << " " << x.z;
  return value ? value->y : 0.0;
}

/// Errors at one distance from the blocks: relative, over the points the blocks leave at
/// least kLit of the light they would get without them; and over all points, relative to
/// that unoccluded light (points deep in a block's shadow have next to no light to compare).
struct NearBase {
  double distance = 0, worstLit = 0, worstOfUnoccluded = 0;
};
constexpr double kLit = 0.2;

/// Direct light only (the emitters shoot once each), default settings otherwise: the worst
/// relative error of the displayed floor value at points `distances` mm out from the middle
/// of every block side's base, against ρ·E·(exact visible factor). `adaptive` false: the
/// uniform mesh graded along the contact lines, and the hemicubes' direct light shown.
std::vector<NearBase> floorNearBlocks(bool cutContacts, bool adaptive,
                                      const std::vector<double>& distances) {
  Scene scene = loadScene(kScenes + "cornell.json");
  Settings settings = resolveSettings(scene, SolverBlock{});
  settings.cutContacts = cutContacts;
  settings.adaptive = settings.vertexDirect = adaptive;
  MeshedScene meshed = meshScene(scene, settings);
  const PatchMesh& mesh = meshed.mesh;
  int floor = -1, emitterPatches = 0;
  for (size_t s = 0; s < scene.surfaces.size(); ++s)
    if (scene.surfaces[s].name == "floor") floor = int(s);
  for (const auto& p : mesh.patches) emitterPatches += luminance(mesh.emission(p.elements[0])) > 0;
  SolverOptions options;
  options.maxShots = emitterPatches;
  HemicubeFactors factors(mesh, settings.hemicubeResolution, scene.diagonal(), settings.seed, 0,
                          settings.emitterHemicubeResolution);
  ProgressiveSolver solver(mesh, factors, options);
  solver.run();
  EXPECT_EQ(solver.patchesNeverShot(), int(mesh.patches.size()) - emitterPatches);
  std::unique_ptr<VertexDirect> direct;
  if (meshed.direct)
    direct.reset(new VertexDirect{solver.direct(), meshed.direct->radiosity(), meshed.base.get()});
  std::vector<glm::dvec3> vertexB = vertexRadiosity(mesh, solver.radiosity(), direct.get());

  const double rho = scene.materials[scene.surfaces[floor].material].reflectance.y;
  double E = 0;
  for (const auto& s : scene.surfaces)
    if (s.name == "light") E = scene.materials[s.material].emission.y;
  std::vector<NearBase> out;
  for (double d : distances) {
    NearBase row;
    row.distance = d;
    for (const auto& s : scene.surfaces) {
      if (s.name.find("_block_side_") == std::string::npos) continue;
      const Ring& q = s.polygons[0].outer;  // bottom edge: the two corners at y = 0
      glm::dvec3 a(0.0), b(0.0);
      int found = 0;
      for (const auto& p : q)
        if (p.y == 0) (found++ ? b : a) = p;
      EXPECT_EQ(found, 2);
      glm::dvec3 n = glm::normalize(glm::cross(q[1] - q[0], q[2] - q[0]));  // outwards
      glm::dvec3 x = (a + b) * 0.5 + glm::normalize(glm::dvec3(n.x, 0, n.z)) * d;
      const double exact = rho * E * visibleLightFactor(scene, x);
      const double open = rho * E * visibleLightFactor(scene, x, false);
      const double shown = floorValue(mesh, floor, vertexB, x);
      if (exact >= kLit * open) row.worstLit = std::max(row.worstLit, std::abs(shown - exact) / exact);
      row.worstOfUnoccluded = std::max(row.worstOfUnoccluded, std::abs(shown - exact) / open);
    }
    out.push_back(row);
  }
  return out;
}

/// The floor 4 mm from a block's base is within 5 % of the exact direct light once the floor
/// is cut at the block, whether graded by adaptive refinement (the default) or beforehand
/// along the contact lines; uncut, the dark vertices under the block pull it far down.
TEST(ContactTest, FloorNextToTheBlocksMatchesTheExactDirectLight) {
  const std::vector<double> distances = {4, 10, 25, 60};
  auto adaptive = floorNearBlocks(true, true, distances);
  auto graded = floorNearBlocks(true, false, distances);
  auto uncut = floorNearBlocks(false, false, distances);
  for (size_t i = 0; i < distances.size(); ++i)
    std::printf("floor %2.0f mm from a block's base, worst error: lit points %.1f %% adaptive, "
                "%.1f %% graded, %.1f %% uncut; all points, of the unoccluded light, %.1f %% "
                "adaptive, %.1f %% graded, %.1f %% uncut\n",
                distances[i], 100 * adaptive[i].worstLit, 100 * graded[i].worstLit,
                100 * uncut[i].worstLit, 100 * adaptive[i].worstOfUnoccluded,
                100 * graded[i].worstOfUnoccluded, 100 * uncut[i].worstOfUnoccluded);
  EXPECT_LE(adaptive[0].worstLit, kNearBaseTolerance);
  EXPECT_LE(graded[0].worstLit, kNearBaseTolerance);
  EXPECT_GT(uncut[0].worstLit, kNearBaseTolerance);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

/// True when no element of `surface` is crossed by the segment where `coordinate` (0 x, 1 y,
/// 2 z) equals `at` and `other` runs over [from, to]: the mesh has element edges along it.
bool meshFollowsLine(const PatchMesh& mesh, int surface, int coordinate, double at, int other,
                     double from, double to, double tolerance) {
  for (int e = 0; e < mesh.elementCount(); ++e) {
    if (mesh.surface(e) != surface) continue;
    auto c = mesh.corners(e);
    bool below = false, above = false;
    double lo = HUGE_VAL, hi = -HUGE_VAL;  // where the line crosses the element, along `other`
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 &p = c[k], &q = c[(k + 1) % 3];
      double dp = p[coordinate] - at, dq = q[coordinate] - at;
      below = below || dp < -tolerance;
      above = above || dp > tolerance;
      if ((dp < -tolerance && dq > tolerance) || (dp > tolerance && dq < -tolerance)) {
        double x = p[other] + (q[other] - p[other]) * dp / (dp - dq);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      if (std::abs(dp) <= tolerance) lo = std::min(lo, p[other]), hi = std::max(hi, p[other]);
    }
    if (below && above && std::min(hi, to) - std::max(lo, from) > tolerance) return false;
  }
  return true;
}

/// scenes/contacts.json: a 200×200 box sunk 100 into the floor and a board leaning against the
/// back wall. The floor inside the box is cut away, exactly its footprint; the box's sides are
/// cut where they pierce the floor; the floor and the wall have element edges along the lines
/// where the board rests on them, and lose no area to it; the ledger balances.
TEST(ContactTest, HalfSunkBoxAndLeaningBoard) {
  Scene scene = loadScene(kScenes + "contacts.json");
  Settings settings = resolveSettings(scene, SolverBlock{});
  PatchMesh mesh = buildPatchMesh(scene, settings.mesh());
  std::map<std::string, int> index;
  for (size_t s = 0; s < scene.surfaces.size(); ++s) index[scene.surfaces[s].name] = int(s);
  const double tolerance = 1e-9 * scene.diagonal();

  ASSERT_EQ(mesh.cutAway.size(), 1u);
  EXPECT_EQ(mesh.cutAway[0].surface, index["floor"]);
  EXPECT_NEAR(mesh.cutAway[0].area / (200.0 * 200.0), 1.0, 1e-9);
  std::vector<int> sides;
  for (int k = 1; k <= 4; ++k) sides.push_back(index["sunk_box_side_" + std::to_string(k)]);
  std::sort(sides.begin(), sides.end());
  EXPECT_EQ(mesh.cutAway[0].enclosedBy, sides);
  for (int e = 0; e < mesh.elementCount(); ++e) {
    if (mesh.surface(e) != index["floor"]) continue;
    glm::dvec3 c = mesh.centroid(e);
    EXPECT_FALSE(c.x > 200 && c.x < 400 && c.z > 300 && c.z < 500) << "floor inside the box";
  }
  // The box's sides pierce the floor at y = 0.
  for (int side : sides) EXPECT_TRUE(meshFollowsLine(mesh, side, 1, 0.0, 0, 200, 400, tolerance) &&
                                     meshFollowsLine(mesh, side, 1, 0.0, 2, 300, 500, tolerance));
  // The board rests on the floor along z = 750 and on the back wall along y = 400, x in
  // [550, 850].
  EXPECT_TRUE(meshFollowsLine(mesh, index["floor"], 2, 750, 0, 550, 850, tolerance));
  EXPECT_TRUE(meshFollowsLine(mesh, index["back_wall"], 1, 400, 0, 550, 850, tolerance));
  // Neither loses area to the board: the floor loses the footprint only.
  double floorArea = 0, wallArea = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) {
    if (mesh.surface(e) == index["floor"]) floorArea += mesh.area(e);
    if (mesh.surface(e) == index["back_wall"]) wallArea += mesh.area(e);
  }
  EXPECT_NEAR(floorArea / (1000.0 * 1000 - 200 * 200), 1.0, 1e-9);
  EXPECT_NEAR(wallArea / (1000.0 * 600), 1.0, 1e-9);

  SolverOptions options;
  options.maxShots = 60;
  HemicubeFactors factors(mesh, 64, scene.diagonal(), 1);
  ProgressiveSolver solver(mesh, factors, options);
  while (solver.step()) ASSERT_LE(solver.ledger().residual(), 1e-9);
  EXPECT_EQ(solver.shots(), 60);
}

/// A box from an OBJ file resting on a floor: the floor under it is cut away, face by face
/// the same as for scene polygons.
TEST(ContactTest, MeshFileBoxOnAFloor) {
  Scene scene = loadScene(std::string(RAD_SOURCE_DIR) + "/tests/data/box_on_floor.json");
  PatchMesh mesh = buildPatchMesh(scene, resolveSettings(scene, SolverBlock{}).mesh());
  ASSERT_EQ(mesh.cutAway.size(), 1u);
  EXPECT_EQ(scene.surfaces[mesh.cutAway[0].surface].name, "floor");
  EXPECT_NEAR(mesh.cutAway[0].area / (100.0 * 100.0), 1.0, 1e-9);
  ASSERT_EQ(mesh.cutAway[0].enclosedBy.size(), 1u);
  EXPECT_EQ(scene.surfaces[mesh.cutAway[0].enclosedBy[0]].name, "box");
}

/// A black surface shows no light: within one element (the floor 500 mm across, elements up
/// to 800 mm), cut where a box stands on it, it is meshed as it is (its boundary's points, no
/// refinement for shape), with the same area as in any other colour.
TEST(ContactTest, ABlackSurfaceWithinAnElementIsMeshedAsItIs) {
  auto floorOf = [](bool black) {
    Scene scene = loadScene(std::string(RAD_SOURCE_DIR) + "/tests/data/box_on_floor.json");
    if (black) {
      scene.materials.push_back(scene.materials[0]);
      scene.materials.back().reflectance = glm::dvec3(0.0);
      scene.surfaces[0].material = int(scene.materials.size()) - 1;
    }
    SolverBlock flags;
    flags.maxElementEdge = 800;
    const PatchMesh mesh = buildPatchMesh(scene, resolveSettings(scene, flags).mesh());
    int elements = 0;
    double area = 0;
    for (int e = 0; e < mesh.elementCount(); ++e)
      if (mesh.surface(e) == 0) ++elements, area += mesh.area(e);
    return std::pair{elements, area};
  };
  const auto [white, whiteArea] = floorOf(false);
  const auto [black, blackArea] = floorOf(true);
  std::printf("floor under a box: %d elements white, %d black\n", white, black);
  EXPECT_LT(black, white);  // measured: 8 against 12
  EXPECT_NEAR(blackArea / whiteArea, 1.0, 1e-9);
}

/// A wall with a doorway standing on a floor touches it along two stretches, not across the
/// doorway: the floor gets element edges under the wall and none across the doorway, and
/// nothing is cut away (the wall's back faces one side of the floor, which stays open).
TEST(ContactTest, WallWithADoorwayTouchesAlongTwoStretches) {
  Scene scene;
  scene.materials.resize(2);
  scene.materials[0].reflectance = glm::dvec3(0.5);
  scene.materials[1].emission = glm::dvec3(1.0);
  auto surface = [&](const std::string& name, int material, Ring outer) {
    Surface s;
    s.name = name;
    s.material = material;
    s.where = name;
    s.polygons.push_back({std::move(outer), {}});
    scene.surfaces.push_back(std::move(s));
  };
  surface("floor", 0, {{0, 0, 0}, {0, 0, 1000}, {1000, 0, 1000}, {1000, 0, 0}});
  surface("light", 1, {{400, 800, 400}, {600, 800, 400}, {600, 800, 600}, {400, 800, 600}});
  surface("wall", 0, {{100, 0, 500}, {400, 0, 500}, {400, 200, 500}, {600, 200, 500},
                      {600, 0, 500}, {900, 0, 500}, {900, 300, 500}, {100, 300, 500}});
  PatchMesh mesh = buildPatchMesh(scene, {60, 180, true});
  const double tolerance = 1e-9 * scene.diagonal();
  EXPECT_TRUE(mesh.cutAway.empty());
  EXPECT_TRUE(meshFollowsLine(mesh, 0, 2, 500, 0, 100, 400, tolerance));
  EXPECT_TRUE(meshFollowsLine(mesh, 0, 2, 500, 0, 600, 900, tolerance));
  EXPECT_FALSE(meshFollowsLine(mesh, 0, 2, 500, 0, 420, 580, tolerance));
  double floorArea = 0;
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (mesh.surface(e) == 0) floorArea += mesh.area(e);
  EXPECT_NEAR(floorArea / 1e6, 1.0, 1e-9);
}

/// The mesh's area on each surface, by name.
std::map<std::string, double> areaBySurface(const Scene& scene, const PatchMesh& mesh) {
  std::map<std::string, double> area;
  for (int e = 0; e < mesh.elementCount(); ++e) area[scene.surfaces[size_t(mesh.surface(e))].name] += mesh.area(e);
  return area;
}

/// What was cut away from each surface, by name.
std::map<std::string, double> cutBySurface(const Scene& scene, const PatchMesh& mesh) {
  std::map<std::string, double> cut;
  for (const CutAway& c : mesh.cutAway) cut[scene.surfaces[size_t(c.surface)].name] += c.area;
  return cut;
}

/// Whether the two maps hold the same names with values within `relative` of each other.
void expectAreas(const std::map<std::string, double>& got, const std::map<std::string, double>& want) {
  for (const auto& [name, area] : want) {
    ASSERT_TRUE(got.count(name)) << name;
    EXPECT_NEAR(got.at(name) / area, 1.0, 1e-9) << name;
  }
  for (const auto& [name, area] : got) EXPECT_TRUE(want.count(name)) << name << " " << area;
}

/// scenes/doorway.json: a 100 mm partition standing on the floor and touching the ceiling and
/// both side walls, a doorway through it. The jambs and the lintel look into the doorway (open
/// air) and are kept whole, though the wall's two faces close them on two sides; what lies
/// inside the wall is cut away: the floor under it (two pieces, beside the doorway), the strip
/// of ceiling over it and of each side wall beside it.
TEST(ContactTest, DoorwayInAThickWallKeepsItsJambsAndLintel) {
  Scene scene = loadScene(kScenes + "doorway.json");
  PatchMesh mesh = buildPatchMesh(scene, resolveSettings(scene, SolverBlock{}).mesh());
  expectAreas(cutBySurface(scene, mesh), {{"floor", (1600.0 + 1500) * 100}, {"ceiling", 4000.0 * 100},
                                          {"left_wall", 2500.0 * 100}, {"right_wall", 2500.0 * 100}});
  const auto area = areaBySurface(scene, mesh);
  EXPECT_NEAR(area.at("jamb_left") / (2100.0 * 100), 1.0, 1e-9);
  EXPECT_NEAR(area.at("jamb_right") / (2100.0 * 100), 1.0, 1e-9);
  EXPECT_NEAR(area.at("lintel") / (900.0 * 100), 1.0, 1e-9);
  EXPECT_NEAR(area.at("floor") / (4000.0 * 8100 - 3100 * 100), 1.0, 1e-9);
}

/// tests/data/window_wall.json: a room whose back wall is 200 mm thick, with a window through
/// it to the open outside. The sill, the head and both reveals are kept whole; the floor,
/// ceiling and side walls lose exactly the strips inside the thick wall.
TEST(ContactTest, WindowInAThickWallKeepsItsReveals) {
  Scene scene = loadScene(std::string(RAD_SOURCE_DIR) + "/tests/data/window_wall.json");
  PatchMesh mesh = buildPatchMesh(scene, resolveSettings(scene, SolverBlock{}).mesh());
  // The ceiling also loses what the lamp lying on it (600 × 600 mm, in its plane) covers.
  expectAreas(cutBySurface(scene, mesh), {{"floor", 3000.0 * 200}, {"ceiling", 3000.0 * 200 + 600.0 * 600},
                                          {"left_wall", 2500.0 * 200}, {"right_wall", 2500.0 * 200}});
  const auto area = areaBySurface(scene, mesh);
  EXPECT_NEAR(area.at("sill") / (1000.0 * 200), 1.0, 1e-9);
  EXPECT_NEAR(area.at("head") / (1000.0 * 200), 1.0, 1e-9);
  EXPECT_NEAR(area.at("reveal_left") / (900.0 * 200), 1.0, 1e-9);
  EXPECT_NEAR(area.at("reveal_right") / (900.0 * 200), 1.0, 1e-9);
}

}  // namespace
}  // namespace rad
