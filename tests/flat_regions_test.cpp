// Flat regions drawn by their outlines give the hemicube factors that drawing every element
// gives: the same pixels, each resolved to the element its centre's ray meets.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/formfactors/flat_regions.h"
#include "radiosity/formfactors/hemicube.h"
#include "radiosity/gather/final_gather.h"
#include "radiosity/settings.h"
#include "radiosity/solve.h"
#include "tests/support.h"

namespace rad {
namespace {

/// Of a hemicube's factors, drawing regions and drawing elements, this much differs in all
/// (Σ |difference| over the elements) on average and at worst: a pixel whose centre lies
/// within the raster's sub-pixel snapping (1/256 pixel) of an element edge may change sides.
/// (Pixel centres a quarter pixel off give 0.26 and 0.43 at 64 pixels, 0.45 and 0.71 at 32.)
constexpr double kSameFactorsMean = 0.006, kSameFactorsWorst = 0.02;
/// What one surface's elements take in all, and what sky and back faces take, agree to this:
/// only outline edges' pixels may change sides.
constexpr double kSameSurface = 3e-3;

struct Compared {
  double worst = 0, mean = 0, surface = 0;
  int points = 0;
};

/// Hemicubes from every `every`-th element's centroid (its own element and `excluded`
/// excluded), drawing the elements and drawing the regions, compared.
Compared compare(const PatchMesh& mesh, double sceneSize, int resolution, int every, HemicubeCulling culling,
                 std::vector<int> excluded = {}) {
  const HemicubeGeometry geometry = HemicubeGeometry::fromMesh(mesh);
  const FlatRegions regions(mesh, sceneSize);
  Hemicube elements(geometry, resolution, sceneSize), outlines(regions, resolution, sceneSize);
  elements.setCulling(culling);
  outlines.setCulling(culling);
  FormFactors a, b;
  Compared out;
  for (int e = 0; e < mesh.elementCount(); e += every, ++out.points) {
    const double rotation = hemicubeRotation(1, uint64_t(e), 0);
    excluded.push_back(e);
    elements.compute(mesh.centroid(e), mesh.normal(e), rotation, a, excluded);
    outlines.compute(mesh.centroid(e), mesh.normal(e), rotation, b, excluded);
    excluded.pop_back();
    std::map<int, double> difference;
    for (size_t k = 0; k < a.elements.size(); ++k) difference[a.elements[k]] += a.factors[k];
    for (size_t k = 0; k < b.elements.size(); ++k) difference[b.elements[k]] -= b.factors[k];
    double total = 0;
    std::map<int, double> perSurface;
    for (const auto& [element, d] : difference) total += std::abs(d), perSurface[mesh.surface(element)] += d;
    for (const auto& [surface, d] : perSurface) out.surface = std::max(out.surface, std::abs(d));
    EXPECT_NEAR(a.sky + a.backFaces, b.sky + b.backFaces, kSameSurface) << "element " << e;
    EXPECT_NEAR(b.sum(), 1.0, 1e-12) << "element " << e;
    out.worst = std::max(out.worst, total);
    out.mean += total;
  }
  out.mean /= std::max(1, out.points);
  return out;
}

TEST(FlatRegionsTest, TheCornellBoxIsAFewRegionsAndItsFactorsAreTheElements) {
  const Scene scene = loadScene(test::kScenes + "cornell.json");
  const PatchMesh mesh = buildPatchMesh(scene, {30, 90});
  const FlatRegions regions(mesh, scene.diagonal());
  EXPECT_LT(regions.regionCount(), 40u);
  EXPECT_LT(regions.drawn().elementCount() * 10, size_t(mesh.elementCount()));
  for (HemicubeCulling culling : {HemicubeCulling::None, HemicubeCulling::Hidden}) {
    const Compared c = compare(mesh, scene.diagonal(), 64, 47, culling);
    EXPECT_GT(c.points, 50);
    EXPECT_LT(c.mean, kSameFactorsMean);
    EXPECT_LT(c.worst, kSameFactorsWorst);
    EXPECT_LT(c.surface, kSameSurface);
  }
}

/// Elements excluded (a shooter's own) occlude but take nothing, drawn either way: here the
/// light's, seen from the floor and the walls.
TEST(FlatRegionsTest, ExcludedElementsTakeNothing) {
  const Scene scene = loadScene(test::kScenes + "cornell.json");
  const PatchMesh mesh = buildPatchMesh(scene, {30, 90});
  std::vector<int> light;
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (scene.surfaces[size_t(mesh.surface(e))].name == "light") light.push_back(e);
  ASSERT_FALSE(light.empty());
  const Compared c = compare(mesh, scene.diagonal(), 64, 97, HemicubeCulling::None, light);
  EXPECT_LT(c.mean, kSameFactorsMean);
  EXPECT_LT(c.surface, kSameSurface);
  const FlatRegions regions(mesh, scene.diagonal());
  Hemicube hemicube(regions, 64, scene.diagonal());
  FormFactors ff;
  const glm::dvec3 floor(278, 1e-6, 279.5);
  hemicube.compute(floor, {0, 1, 0}, 0.0, ff, light);
  for (int e : ff.elements) EXPECT_NE(scene.surfaces[size_t(mesh.surface(e))].name, "light");
  EXPECT_GT(ff.backFaces, 0.01);  // the light's share, seen but excluded
}

/// Every shipped scene, meshed coarsely: what each surface takes is the same drawn either way
/// (an outline triangulated inside out, holes drawn and surfaces left out, would not be).
TEST(FlatRegionsTest, EveryShippedSceneGivesEachSurfaceItsShare) {
  std::vector<std::string> files = test::sceneFiles("scenes");
  for (const std::string& f : test::sceneFiles("scenes/stress")) files.push_back(f);
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const Scene scene = loadScene(file);
    const PatchMesh mesh = buildPatchMesh(scene, {scene.diagonal() / 20, scene.diagonal() / 10});
    const Compared c = compare(mesh, scene.diagonal(), 32, std::max(1, mesh.elementCount() / 12), HemicubeCulling::None);
    EXPECT_GE(c.points, 10);
    EXPECT_LT(c.surface, kSameSurface);
  }
}

/// Inside a closed cube nothing escapes: where two walls' outlines meet, no pixel falls
/// between them (their corners are the walls' shared mesh vertices).
TEST(FlatRegionsTest, NothingEscapesAClosedCube) {
  const Scene scene = loadScene(test::kScenes + "cube.json");
  const PatchMesh mesh = buildPatchMesh(scene, {0.125, 0.25});
  const FlatRegions regions(mesh, scene.diagonal());
  EXPECT_LE(regions.drawn().elementCount(), 12u);  // six squares, two triangles each
  Hemicube hemicube(regions, 256, scene.diagonal());
  FormFactors ff;
  int tested = 0;
  for (int e = 0; e < mesh.elementCount(); e += 37, ++tested) {
    hemicube.compute(mesh.centroid(e), mesh.normal(e), hemicubeRotation(1, uint64_t(e), 0), ff, {e});
    EXPECT_EQ(ff.sky, 0.0) << "element " << e;
    EXPECT_NEAR(ff.sum(), 1.0, 1e-12) << "element " << e;
  }
  EXPECT_GT(tested, 20);
}

TEST(FlatRegionsTest, CornellBoxOriginalAsTheGatherDrawsIt) {
  Scene scene = loadSceneToSolve(test::kScenes + "cornell_original.json");
  const Settings settings = resolveSettings(scene, {});
  const MeshedScene meshed = meshScene(std::move(scene), settings);
  const PatchMesh& base = meshed.base ? *meshed.base : meshed.mesh;
  const Compared c = compare(base, meshed.scene.diagonal(), kDefaultGatherResolution, 17, HemicubeCulling::None);
  EXPECT_GT(c.points, 400);
  EXPECT_LT(c.mean, kSameFactorsMean);
  EXPECT_LT(c.worst, kSameFactorsWorst);
  EXPECT_LT(c.surface, kSameSurface);
}

}  // namespace
}  // namespace rad
