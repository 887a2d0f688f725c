// Surfaces that pass through others (issue 30): a tread through a wall, a cornice pushed into
// the ceiling and the wall, a frame through a painting (tests/data/piercing/, rooms of 4 × 3 × 4
// m lit by a ceiling lamp); and beside them, narrow gaps and a sphere resting on a floor. Each surface is cut along the line where another passes through it,
// and the two sides of that line get vertices of their own (a seam): the part of the tread
// beyond the wall shows no light, the part in the room shows its own. Checked at defaults
// against path-traced references (`radiosity reference`, stored beside the scenes) at points
// 2 and 5 cm from the lines.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/refine.h"
#include "tests/solve_support.h"

namespace rad {
namespace {

const std::string kPiercing = test::kData + "piercing/";

/// The shown radiosity 2 and 5 cm from where surfaces pass through each other, RMS over the
/// points of a tag (the reference's own noise is about 0.5 %). Measured: tread top 0.7 %, wall
/// above and below it 0.6 and 0.9 %; cornice scene 1.1 % (2.2 % before the seams: the tread's
/// top showed 34 % too dark at 2 cm, its vertices on the wall's line taking the dark of the
/// tread's part beyond the wall).
constexpr double kNearLineRms = 0.02;
/// Known limit: the wall 2 cm beside the tread's side and under the frame's bars lies in a
/// penumbra 1–3 cm wide (the 4–6 cm part casting it is as close), narrower than the smallest
/// element adaptive refinement makes (element edge / 8, 3.3 cm here). Measured worst: −12 %
/// beside the tread, −6.7 % on the painting, −4.7 % on the wall under the frame.
constexpr double kThinPenumbraWorst = 0.15;
/// Round a fixture hanging 9 mm under the ceiling, 1 to 20 cm from its outline, and on the floor
/// 1 to 20 cm beside a sofa standing 6 mm above it (tests/data/piercing/narrow_gap.json): RMS and
/// worst point. Measured: ceiling 4.4 % RMS, worst −10.2 % (before the gaps' mouths were
/// refined: 14.8 %, −35 %); floor beside the sofa 4.2 %, worst −14 % at 1 cm (before its
/// vertices gathered through their own hemicubes: 15.8 %, −32 %). Under the sofa, 1 to 20 cm
/// inside its edge, the light falls off within a centimetre or two and is shown 2 to 100×
/// too bright: a known limit (the elements there are no smaller than the smallest element,
/// 3.3 cm, and the sofa's underside is not refined), not tested.
constexpr double kGapRms = 0.07;
constexpr double kGapWorst = 0.2;
/// The floor in the shadow of a sphere resting on it, lit by a panel on a wall, 0.4 to 1.9 m
/// behind it (tests/data/piercing/sphere.json): RMS and worst point, the targets.
/// Measured 1.26 % and −4.8 %. Known limit, not tested: the floor within 10 cm of the point the
/// sphere rests on (a wedge of a gap, 0.7 mm high 2 cm out, 17 mm at 10 cm) is shown 3.6×
/// too bright in RMS, 12× at worst 2 cm out (9.5× and 27× before refined vertices beside a
/// surface gathered for themselves): the light there falls off over a centimetre or two,
/// finer than the elements.
constexpr double kCurvedShadowRms = 0.02;
constexpr double kCurvedShadowWorst = 0.1;
/// A vertex on a seam shows at least this share of the median of its neighbours on its side.
constexpr double kSeamVertexShare = 0.5;

int surfaceNamed(const Scene& scene, const std::string& name) {
  for (size_t s = 0; s < scene.surfaces.size(); ++s)
    if (scene.surfaces[s].name == name) return int(s);
  return -1;
}

/// The tread's top vertices (normal up) on the wall's plane x = −2, by position.
std::map<std::array<double, 3>, std::vector<TriMesh::VertexHandle>> treadTopOnTheWall(const PatchMesh& pm, int tread) {
  std::map<std::array<double, 3>, std::vector<TriMesh::VertexHandle>> at;
  for (auto v : pm.mesh.vertices()) {
    const auto p = pm.mesh.point(v);
    if (p[0] != -2.0 || p[1] != 0.56) continue;
    bool top = false;
    for (auto f : pm.mesh.vf_range(v)) top = top || (pm.surface(f.idx()) == tread && pm.normal(f.idx()).y > 0.9);
    if (top) at[{p[0], p[1], p[2]}].push_back(v);
  }
  return at;
}

/// Whether vertex v's elements lie in the room (x > −2).
bool inTheRoom(const PatchMesh& pm, TriMesh::VertexHandle v) {
  for (auto f : pm.mesh.vf_range(v))
    if (pm.centroid(f.idx()).x < -2.0) return false;
  return true;
}

/// Meshed as `radiosity solve` meshes it, the tread's top has two vertices at every point of the
/// wall's line across it, one per side; no patch reaches across; the mesh stays conforming.
TEST(PiercingTest, TreadIsSplitAlongTheWall) {
  Scene scene = loadSceneToSolve(kPiercing + "tread.json");
  const Settings settings = resolveSettings(scene, SolverBlock{});
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  const PatchMesh& pm = meshed.mesh;
  const int tread = surfaceNamed(meshed.scene, "tread");
  ASSERT_GE(tread, 0);
  const auto onLine = treadTopOnTheWall(pm, tread);
  EXPECT_GE(onLine.size(), 9u);  // the 1 m line split at least every element edge / 8
  for (const auto& [p, vertices] : onLine) {
    ASSERT_EQ(vertices.size(), 2u) << "at z = " << p[2];
    EXPECT_NE(inTheRoom(pm, vertices[0]), inTheRoom(pm, vertices[1])) << "at z = " << p[2];
    for (auto v : vertices) EXPECT_TRUE(pm.seam(v));
  }
  for (const Patch& patch : pm.patches) {
    if (patch.surface != tread) continue;
    int inside = 0;
    for (int e : patch.elements) inside += pm.centroid(e).x > -2.0;
    EXPECT_TRUE(inside == 0 || inside == int(patch.elements.size())) << "a tread patch reaches through the wall";
  }
  const auto found = findTJunctions(pm, 1e-7, true);
  EXPECT_TRUE(found.empty()) << found.size() << " T-junctions";
}

/// The tread through the wall at defaults: right beside the line on both surfaces, and no vertex
/// on the tread's seam, on the room's side, darker than half its neighbours' median.
TEST(PiercingTest, TreadThroughAWallAtDefaults) {
  const auto s = test::solveLikeCli(kPiercing + "tread.json");
  const std::string reference = kPiercing + "tread_reference.csv";
  for (const char* tag : {"tread_top", "wall_above", "wall_below"})
    EXPECT_LE(test::trueError(*s, reference, tag), kNearLineRms) << tag;
  EXPECT_LE(std::abs(test::trueErrorOf(*s, reference, "wall_side").worst), kThinPenumbraWorst);
  const PatchMesh& pm = s->meshed.mesh;
  const int tread = surfaceNamed(s->meshed.scene, "tread");
  int checked = 0;
  for (const auto& [p, vertices] : treadTopOnTheWall(pm, tread))
    for (auto v : vertices) {
      if (!inTheRoom(pm, v)) continue;
      std::vector<double> around;
      for (auto w : pm.mesh.vv_range(v)) around.push_back(luminance(s->shown[size_t(w.idx())]));
      std::nth_element(around.begin(), around.begin() + long(around.size() / 2), around.end());
      EXPECT_GE(luminance(s->shown[size_t(v.idx())]), kSeamVertexShare * around[around.size() / 2]) << "at z = " << p[2];
      ++checked;
    }
  EXPECT_GE(checked, 9);
}

/// A cornice pushed into the ceiling and the wall: right on all four sides of its lines.
TEST(PiercingTest, CornicePushedIntoTheCeilingAtDefaults) {
  const auto s = test::solveLikeCli(kPiercing + "cornice.json");
  const std::string reference = kPiercing + "cornice_reference.csv";
  for (const char* tag : {"ceiling", "wall", "cornice_face", "cornice_under"})
    EXPECT_LE(test::trueError(*s, reference, tag), kNearLineRms) << tag;
}

/// A frame through a painting 1 mm off the wall: its front is right; the painting and the wall
/// beside its bars lie in the bars' thin penumbrae (kThinPenumbraWorst).
TEST(PiercingTest, FrameThroughAPaintingAtDefaults) {
  const auto s = test::solveLikeCli(kPiercing + "frame.json");
  const std::string reference = kPiercing + "frame_reference.csv";
  EXPECT_LE(test::trueError(*s, reference, "frame_front"), kNearLineRms);
  for (const char* tag : {"painting", "wall"})
    EXPECT_LE(std::abs(test::trueErrorOf(*s, reference, tag).worst), kThinPenumbraWorst) << tag;
}

/// Narrow gaps: the ceiling round a fixture just under it, the floor beside a sofa just above
/// it (kGapRms, kGapWorst).
TEST(PiercingTest, NarrowGapsAtDefaults) {
  const auto s = test::solveLikeCli(kPiercing + "narrow_gap.json");
  const std::string reference = kPiercing + "narrow_gap_reference.csv";
  for (const char* tag : {"ceiling_ring", "gap_beside"}) {
    const auto error = test::trueErrorOf(*s, reference, tag);
    EXPECT_LE(error.rms, kGapRms) << tag;
    EXPECT_LE(std::abs(error.worst), kGapWorst) << tag;
  }
}

/// A curved occluder's shadow: a sphere on the floor (kCurvedShadowRms, kCurvedShadowWorst).
TEST(PiercingTest, SphereOnAFloorCastsItsShadowAtDefaults) {
  const auto s = test::solveLikeCli(kPiercing + "sphere.json");
  const auto shadow = test::trueErrorOf(*s, kPiercing + "sphere_reference.csv", "shadow");
  EXPECT_GE(shadow.used, 80);
  EXPECT_LE(shadow.rms, kCurvedShadowRms);
  EXPECT_LE(std::abs(shadow.worst), kCurvedShadowWorst);
}

/// Faces lying on faces (tests/data/piercing/faces_on_faces.json: a 2 × 2 m rug on a floor
/// that the file has twice): where they overlap the one in front wins (the smaller surface; of
/// two alike, the later in the file) and what it covers is left out, so nothing ties in depth
/// with it (no z-fighting in a hemicube or the viewer).
TEST(PiercingTest, FacesLyingOnFacesLeaveOutWhatTheyCover) {
  Scene scene = loadSceneToSolve(kPiercing + "faces_on_faces.json");
  const Settings settings = resolveSettings(scene, SolverBlock{});
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  auto area = [&](const char* name) { return meshed.mesh.surfaces[size_t(surfaceNamed(meshed.scene, name))].area; };
  EXPECT_EQ(meshed.mesh.surfaces[size_t(surfaceNamed(meshed.scene, "floor"))].elements, 0);
  EXPECT_NEAR(area("floor_again"), 16.0 - 4.0, 1e-9);
  EXPECT_NEAR(area("rug"), 4.0, 1e-9);
  double cut = 0;
  for (const CutAway& c : meshed.mesh.cutAway) cut += c.area;
  EXPECT_NEAR(cut, 16.0 + 4.0, 1e-9);
}

/// The same at defaults, 2, 5 and 30 cm either side of the rug's edge: the reference's rays
/// meet the same surfaces (measured 0.5 % RMS; 1.4 % against a reference whose rays met
/// whichever of the coplanar faces came first).
TEST(PiercingTest, FacesLyingOnFacesAtDefaults) {
  const auto s = test::solveLikeCli(kPiercing + "faces_on_faces.json");
  const std::string reference = kPiercing + "faces_on_faces_reference.csv";
  for (const char* tag : {"floor", "rug"}) EXPECT_LE(test::trueError(*s, reference, tag), kNearLineRms) << tag;
}

/// A box standing on a floor made of two triangles whose diagonal runs under it
/// (tests/data/piercing/box_on_split_floor.json): its footprint is left out of both, each half
/// enclosed by the box's sides and the diagonal the two triangles share.
TEST(PiercingTest, FootprintOverTwoFacesOfAFloorIsLeftOut) {
  Scene scene = loadSceneToSolve(kPiercing + "box_on_split_floor.json");
  const Settings settings = resolveSettings(scene, SolverBlock{});
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  const int floor = surfaceNamed(meshed.scene, "floor");
  double cut = 0;
  int parts = 0;
  for (const CutAway& c : meshed.mesh.cutAway)
    if (c.surface == floor) cut += c.area, ++parts;
  EXPECT_EQ(parts, 2);
  EXPECT_NEAR(cut, 1.0, 1e-9);
  EXPECT_NEAR(meshed.mesh.surfaces[size_t(floor)].area, 16.0 - 1.0, 1e-9);
}

}  // namespace
}  // namespace rad
