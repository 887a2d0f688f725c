// Adaptive subdivision: conforming output meshes, the energy ledger and the furnace after
// refinement, shadow boundaries where geometry puts them, and no refinement where nothing
// changes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/base/color.h"
#include "mesh/base/error.h"
#include "mesh/refine.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/adaptive.h"
#include "radiosity/formfactors/point_polygon.h"
#include "radiosity/result.h"
#include "radiosity/settings.h"
#include "radiosity/shooting/progressive_solver.h"
#include "tests/solve_support.h"

namespace rad {
namespace {

using test::kScenes;
constexpr double kLedger = 1e-9;

/// Every scene the project ships and tests with, meshed as `radiosity solve` meshes it
/// (adaptive refinement on): no vertex inside another element's edge, of its own surface
/// side or, where surfaces meet, of another.
TEST(AdaptiveTest, EveryOutputMeshIsConforming) {
  std::vector<std::string> paths;
  for (const char* dir : {"scenes", "scenes/stress", "tests/data", "tests/data/piercing"})
    for (const auto& path : test::sceneFiles(dir)) paths.push_back(path);
  ASSERT_GE(paths.size(), 20u);
  int refined = 0;
  for (const auto& path : paths) {
    Scene scene;
    try {
      scene = loadScene(path);
    } catch (const InputError&) {
      continue;  // the invalid examples of tests/data
    }
    Settings settings = resolveSettings(scene, SolverBlock{});
    MeshedScene meshed = meshScene(scene, settings);
    refined += meshed.adaptive.elementsAfter > meshed.adaptive.elementsBefore;
    auto found = findTJunctions(meshed.mesh, 1e-7, true);
    EXPECT_TRUE(found.empty()) << path << ": " << found.size() << " T-junctions, the first at vertex "
                               << (found.empty() ? -1 : found[0].vertex);
  }
  EXPECT_GE(refined, 5);  // the check saw refined meshes, not only untouched ones
}

/// The Cornell box, refined: the ledger closes after every shot, the meshed area is the
/// surfaces' area, and no radiosity is negative or NaN.
TEST(AdaptiveTest, LedgerBalancesAfterRefinement) {
  auto s = test::solveLikeCli(kScenes + "cornell.json");
  const PatchMesh& mesh = s->meshed.mesh;
  EXPECT_GT(s->meshed.adaptive.elementsAfter, 2 * s->meshed.adaptive.elementsBefore);
  EXPECT_GT(s->meshed.adaptive.rounds, 1);
  EXPECT_LE(s->solver().ledger().residual(), kLedger);
  // The iterated final gather's progressive start: a hundredth of a shot per patch (the
  // gather converges from it).
  EXPECT_EQ(s->solver().stopReason(), ProgressiveSolver::Stop::MaxShots);
  EXPECT_EQ(s->solver().shots(), long(std::ceil(kIteratedStartShotsPerPatch * double(mesh.patches.size()))));
  for (size_t sf = 0; sf < mesh.surfaces.size(); ++sf) {
    double area = 0;
    for (int e = 0; e < mesh.elementCount(); ++e)
      if (mesh.surface(e) == int(sf) && mesh.side(e) == 0) area += mesh.area(e);
    EXPECT_NEAR(area / mesh.surfaces[sf].area, 1.0, 1e-9) << sf;
  }
  for (const auto& b : s->shown) {
    EXPECT_TRUE(std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.z));
    EXPECT_GE(std::min({b.x, b.y, b.z}), 0.0);
  }
}

/// The furnace (oracles.md §4: one glowing closed cube) needs no refinement: nothing changes
/// across it. Every patch glows: rays from the vertices to every one of them would cost more
/// than they show (kMaxRayEmitterPatches), so none are cast; with patches wide enough to be
/// few, the rays' direct light at every vertex is ρ·E, the exact factors to the five other
/// faces summing to one (at the cube's edges too: the limit from inside each face). That
/// refined elements still hold the furnace: FurnaceTest.HoldsAfterRefinement.
TEST(AdaptiveTest, FurnaceNeedsNoRefinement) {
  const Scene furnace = loadScene(kScenes + "furnace.json");
  const MeshedScene many = meshScene(furnace, resolveSettings(furnace, {}));
  EXPECT_EQ(many.adaptive.elementsAfter, many.adaptive.elementsBefore);
  EXPECT_EQ(many.direct, nullptr);
  ASSERT_FALSE(many.mesh.warnings.empty());  // and the user is told
  EXPECT_NE(many.mesh.warnings.back().find("adaptive subdivision off"), std::string::npos);
  SolverBlock flags;
  flags.maxPatchEdge = 0.5;
  const MeshedScene few = meshScene(furnace, resolveSettings(furnace, flags));
  EXPECT_EQ(few.adaptive.elementsAfter, few.adaptive.elementsBefore);
  ASSERT_NE(few.direct, nullptr);
  constexpr double kExactSum = 1e-4;  // the rays start 1e-5 of the scene size inwards
  for (const auto& d : few.direct->radiosity()) EXPECT_NEAR(d.x, 0.5, 0.5 * kExactSum);
}

/// The longest edge of the ceiling elements (y = 3) of a meshed narrow_gap.json that reach from
/// over its fixture, `inside` within its outline (|x|, |z| < 0.3 − inside), out past it (|x| or
/// |z| > 0.3): across the mouth of the 9 mm gap (0: none).
double longestAcrossTheFixturesOutline(const PatchMesh& mesh, double inside) {
  double longest = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) {
    const auto c = mesh.corners(e);
    if (c[0].y != 3 || c[1].y != 3 || c[2].y != 3) continue;
    bool over = false, past = false;
    for (const auto& p : c) {
      over = over || (std::abs(p.x) < 0.3 - inside && std::abs(p.z) < 0.3 - inside);
      past = past || std::abs(p.x) > 0.3 || std::abs(p.z) > 0.3;
    }
    if (over && past) longest = std::max(longest, longestEdge(mesh, e));
  }
  return longest;
}

/// Gaps' mouths: the ceiling elements that reach from over a fixture hanging 9 mm under it (a
/// smallest element within its outline or more) out past it (the direct light none on either
/// side) are refined away when gaps are looked for (none is left that long); refining the same
/// mesh without looking for them leaves one 7.8 smallest elements long. As `radiosity solve`
/// refines: the same mesh, light and options but for AdaptiveOptions::gapReach.
TEST(AdaptiveTest, GapsMouthsRefinedWhenLookedFor) {
  const Scene scene = loadSceneToSolve(test::kData + "piercing/narrow_gap.json");
  const Settings settings = resolveSettings(scene, {});
  SolverBlock flags;
  flags.adaptive = false;
  const MeshedScene unrefined = meshScene(scene, resolveSettings(scene, flags));
  const double smallest = settings.minElementEdge;
  auto refinedWith = [&](double gapReach) {
    PatchMesh mesh = unrefined.mesh;
    DirectLight light(mesh, unrefined.scene.diagonal());
    AdaptiveOptions options;
    options.minElementEdge = smallest;
    options.contrast = settings.contrast;
    options.gapReach = gapReach;
    refineAdaptively(mesh, light, options);
    return mesh;
  };
  EXPECT_GT(longestAcrossTheFixturesOutline(refinedWith(0), smallest), 3 * smallest);
  EXPECT_EQ(longestAcrossTheFixturesOutline(refinedWith(smallest), smallest), 0);
}

/// The exact visible factor of scenes/penumbra.json's light from floor point x: the light's
/// minus the part the 60×60 square 100 above the floor hides (the square projected from x,
/// scale 2, clipped to the light).
double penumbraVisibleFactor(const glm::dvec3& x) {
  auto rect = [](double x0, double x1, double z0, double z1) {
    return std::vector<glm::dvec3>{{x0, 200, z0}, {x1, 200, z0}, {x1, 200, z1}, {x0, 200, z1}};
  };
  double f = pointPolygonFormFactor(x, {0, 1, 0}, rect(-50, 50, -50, 50));
  double x0 = std::max(-50.0, -60 - x.x), x1 = std::min(50.0, 60 - x.x);
  double z0 = std::max(-50.0, -60 - x.z), z1 = std::min(50.0, 60 - x.z);
  if (x0 < x1 && z0 < z1) f -= pointPolygonFormFactor(x, {0, 1, 0}, rect(x0, x1, z0, z1));
  return f;
}

/// scenes/penumbra.json meshed from 24 mm elements down to 3 mm: along the floor's middle
/// line, where the shown light first rises above 2 % of the unoccluded light (the umbra's
/// edge, geometrically at 10) and where it reaches 98 % (the penumbra's outer edge, at 110)
/// are where the exact visible factor puts them, within one minimum element edge; with
/// fewer elements than a uniform mesh at that edge.
TEST(AdaptiveTest, PenumbraBoundariesWithinOneMinimumElement) {
  constexpr double kBase = 24, kMin = 3;
  SolverBlock flags;
  flags.maxElementEdge = kBase;
  flags.minElementEdge = kMin;
  auto s = test::solveLikeCli(kScenes + "penumbra.json", flags);
  const PatchMesh& mesh = s->meshed.mesh;
  std::vector<int> floor;
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (s->meshed.scene.surfaces[size_t(mesh.surface(e))].name == "floor") floor.push_back(e);
  const double rho = 0.5;
  const std::vector<glm::dvec3> light = {{-50, 200, -50}, {50, 200, -50}, {50, 200, 50}, {-50, 200, 50}};
  for (int axis : {0, 2}) {
    // First crossings going outwards from the middle, on both halves of the line.
    for (double sign : {-1.0, 1.0}) {
      double shownUmbra = NAN, exactUmbra = NAN, shownOuter = NAN, exactOuter = NAN;
      for (double t = 0; t <= 140; t += 0.25) {
        glm::dvec3 x(0.0);
        x[axis] = sign * t;
        const double open = rho * pointPolygonFormFactor(x, {0, 1, 0}, light);
        const double shown = gouraudAt(mesh, floor, s->shown, x).value_or(glm::dvec3(NAN)).x / open;
        const double exact = rho * penumbraVisibleFactor(x) / open;
        if (std::isnan(shownUmbra) && shown > 0.02) shownUmbra = t;
        if (std::isnan(exactUmbra) && exact > 0.02) exactUmbra = t;
        if (std::isnan(shownOuter) && shown >= 0.98) shownOuter = t;
        if (std::isnan(exactOuter) && exact >= 0.98) exactOuter = t;
      }
      std::printf("axis %d, side %+.0f: umbra edge shown at %.2f, exact %.2f; penumbra edge shown at "
                  "%.2f, exact %.2f\n", axis, sign, shownUmbra, exactUmbra, shownOuter, exactOuter);
      // The exact 2 % crossing itself: 10 (the umbra's edge) plus the few millimetres over
      // which the first 2 % of the light comes into view.
      EXPECT_NEAR(exactUmbra, 10, 3);
      EXPECT_NEAR(shownUmbra, exactUmbra, kMin);
      EXPECT_NEAR(shownOuter, exactOuter, kMin);
    }
  }
  const PatchMesh uniform = buildPatchMesh(s->meshed.scene, {kMin, s->meshed.settings.maxPatchEdge, true, 1});
  std::printf("penumbra scene: %d elements adaptive, %d uniform at the minimum edge\n",
              mesh.elementCount(), uniform.elementCount());
  EXPECT_LT(mesh.elementCount(), uniform.elementCount() / 3);
  EXPECT_TRUE(findTJunctions(mesh).empty());
}

/// scenes/penumbra.json from 24 mm elements with a 12 mm floor: the umbra's edge, where the
/// shown light rises from nothing within millimetres, is a sharp change (kSharpContrast times
/// the contrast across an element), so elements there go under the floor, to a quarter of it
/// at most; out in the full light beyond the penumbra (110 mm from the middle), where the
/// light changes slowly, none does.
TEST(AdaptiveTest, SharpChangesRefineUnderTheFloor) {
  constexpr double kBase = 24, kFloor = 12;
  const Scene scene = loadSceneToSolve(kScenes + "penumbra.json");
  SolverBlock flags;
  flags.maxElementEdge = kBase;
  flags.adaptive = false;
  const MeshedScene unrefined = meshScene(scene, resolveSettings(scene, flags));
  PatchMesh mesh = unrefined.mesh;
  DirectLight light(mesh, unrefined.scene.diagonal());
  AdaptiveOptions options;
  options.minElementEdge = kFloor;
  refineAdaptively(mesh, light, options);
  int under = 0;
  double shortest = HUGE_VAL;
  for (int e = 0; e < mesh.elementCount(); ++e) {
    if (unrefined.scene.surfaces[size_t(mesh.surface(e))].name != "floor") continue;
    const double edge = longestEdge(mesh, e);
    shortest = std::min(shortest, edge);
    if (edge >= kFloor / 2) continue;  // what bisecting elements over the floor gives
    ++under;
    const glm::dvec3 c = mesh.centroid(e);
    EXPECT_LT(std::max(std::abs(c.x), std::abs(c.z)), 110) << "under the floor in the full light at " << c.x << " " << c.z;
  }
  std::printf("penumbra at a 12 mm floor: %d floor elements under half the floor, the shortest %.2f mm\n", under,
              shortest);
  EXPECT_GT(under, 0);
  EXPECT_GE(shortest, kFloor / kSharpRefinement / 4);  // (a quarter of the floor halved is the least by design)
  EXPECT_TRUE(findTJunctions(mesh).empty());
}

}  // namespace
}  // namespace rad
