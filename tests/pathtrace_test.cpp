// The independent reference (radiosity/pathtrace) against exact answers: the furnace, the direct
// light of an empty Cornell box by the exact point-to-polygon factor, the generalised furnace,
// and the honesty of its standard errors (their coverage); and the true error measured against
// it (radiosity/true_error) against the true error measured against the exact answer.
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/adaptive.h"
#include "radiosity/formfactors/point_polygon.h"
#include "radiosity/pathtrace/path_tracer.h"
#include "radiosity/result.h"
#include "radiosity/settings.h"
#include "radiosity/shooting/progressive_solver.h"
#include "radiosity/solve.h"
#include "radiosity/true_error.h"
#include "tests/support.h"

namespace rad::pathtrace {
namespace {

using test::kScenes;

/// An estimate agrees with an exact answer when within this many standard errors.
constexpr double kSigmas = 3;
/// Estimates must be sharp enough for the comparison to mean something.
constexpr double kMaxRelativeSE = 0.02;

/// Every material's reflectance set to rho.
Scene withReflectance(Scene scene, double rho) {
  for (auto& m : scene.materials) m.reflectance = glm::dvec3(rho);
  return scene;
}

/// Points on the scene's surfaces at (u, v) of every polygon's corner frame (a, b − a, d − a),
/// on quads, located on their surface.
std::vector<SurfacePoint> gridPoints(const TraceScene& traced, const std::vector<double>& uv) {
  std::vector<SurfacePoint> out;
  for (const auto& s : traced.scene().surfaces)
    for (const auto& p : s.polygons) {
      const auto& r = p.outer;
      const glm::dvec3 n = glm::normalize(glm::cross(r[1] - r[0], r[3] - r[0]));
      for (double u : uv)
        for (double v : uv) {
          SurfacePoint q{r[0] + u * (r[1] - r[0]) + v * (r[3] - r[0]), n, -1, ""};
          if (locatePoint(traced, q, 1e-6 * traced.size())) out.push_back(q);
        }
    }
  return out;
}

/// An estimate beyond this many standard errors is a bias, not chance (p < 1e-4 per point).
constexpr double kBias = 4;

/// How many channels of e lie beyond kSigmas standard errors of the exact answer; every one
/// must lie within kBias of it and be sharp enough to mean something.
int outside(const glm::dvec3& exact, const PointEstimate& e, const glm::dvec3& at) {
  int count = 0;
  for (int c = 0; c < 3; ++c) {
    const double z = std::abs(e.B[c] - exact[c]) / e.standardError[c];
    EXPECT_LE(z, kBias) << "channel " << c << " at (" << at.x << ", " << at.y << ", " << at.z
                        << "): B " << e.B[c] << ", exact " << exact[c] << ", SE " << e.standardError[c];
    if (exact[c] > 0) {
      EXPECT_LT(e.standardError[c] / exact[c], kMaxRelativeSE);
    }
    count += z > kSigmas;
  }
  return count;
}

void expectWithin(const glm::dvec3& exact, const PointEstimate& e, const glm::dvec3& at) {
  EXPECT_EQ(outside(exact, e, at), 0) << "B (" << e.B.x << ", " << e.B.y << ", " << e.B.z << "), exact ("
                                      << exact.x << ", " << exact.y << ", " << exact.z << ")";
}

/// Furnace (oracles.md §4): a closed cube, every face glowing E = 1 with reflectance ρ:
/// B = E/(1 − ρ) at every point, near edges and corners too: every point within kBias standard
/// errors, and beyond kSigmas no more than chance puts there (0.27 % of 108: at most 2).
/// A floor with a panel lying 0.5 mm above it (a 6 mm gap under a sofa, a lamp hung under a
/// ceiling, at scale), facing `panelUp` or down; the panel is surface 1.
Scene floorUnderAPanel(bool panelUp) {
  const std::string panel = panelUp ? "[[0.2,0.0005,0.2],[0.2,0.0005,0.8],[0.8,0.0005,0.8],[0.8,0.0005,0.2]]"
                                    : "[[0.2,0.0005,0.2],[0.8,0.0005,0.2],[0.8,0.0005,0.8],[0.2,0.0005,0.8]]";
  return parseScene(R"({"version": 1, "materials": {"w": {"reflectance": [0.5, 0.5, 0.5]},
      "l": {"reflectance": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
    "surfaces": [{"name": "floor", "material": "w", "polygon": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]]},
                 {"name": "panel", "material": "w", "polygon": )" + panel + R"(},
                 {"name": "lamp", "material": "l", "polygon": [[0,1,0],[1,1,0],[1,1,1],[0,1,1]]}]})",
                    "gap.json", "");
}

/// A point the user gives on a surface is found however close another surface lies in front of
/// it (its back or its front) or behind it: the nearest surface along the normal whose side faces
/// the normal's way, within the tolerance (here 2 mm, four times the gap).
TEST(ReferenceTest, PointsInANarrowGapAreLocated) {
  for (bool panelUp : {false, true}) {
    const Scene scene = floorUnderAPanel(panelUp);
    const TraceScene traced(scene);
    SurfacePoint onFloor{{0.5, 0.0001, 0.5}, {0, 1, 0}, -1, ""};
    ASSERT_TRUE(locatePoint(traced, onFloor, 0.002)) << "panel up " << panelUp;
    EXPECT_EQ(onFloor.surface, 0);
    EXPECT_NEAR(onFloor.position.y, 0.0, 1e-9);
    if (!panelUp) continue;
    SurfacePoint onPanel{{0.5, 0.0004, 0.5}, {0, 1, 0}, -1, ""};  // nearer the panel's top
    ASSERT_TRUE(locatePoint(traced, onPanel, 0.002));
    EXPECT_EQ(onPanel.surface, 1);
    EXPECT_NEAR(onPanel.position.y, 0.0005, 1e-9);
  }
  // Under a panel facing down, a point just below it facing down is on the panel.
  const Scene panelDown = floorUnderAPanel(false);  // a TraceScene reads the scene it was given
  const TraceScene traced(panelDown);
  SurfacePoint under{{0.5, 0.0004, 0.5}, {0, -1, 0}, -1, ""};
  ASSERT_TRUE(locatePoint(traced, under, 0.002));
  EXPECT_EQ(under.surface, 1);
  // A point facing a surface's back has no surface there.
  SurfacePoint below{{0.5, -0.0001, 0.5}, {0, -1, 0}, -1, ""};
  EXPECT_FALSE(locatePoint(traced, below, 0.00015));
}

/// Surfaces lying on each other in one plane (a rug on a floor that is there twice): a ray meets
/// the one in front, as the mesher keeps it, the smaller surface, and of two alike the later,
/// wherever it comes down; not whichever the ray structure met first.
TEST(ReferenceTest, RaysMeetTheSurfaceInFrontOfCoplanarOnes) {
  const Scene scene = loadScene(test::kData + "piercing/faces_on_faces.json");
  const TraceScene traced(scene);
  auto surfaceBelow = [&](double x, double z) {
    const TraceHit hit = traced.intersect(traced.toLocal({x, 1.0, z}), {0, -1, 0}, 1.0);
    return hit.triangle < 0 ? std::string("nothing") : scene.surfaces[size_t(traced.triangle(hit.triangle).surface)].name;
  };
  for (double x : {-0.9, -0.3, 0.0, 0.4, 0.95})
    for (double z : {-0.9, 0.0, 0.7}) EXPECT_EQ(surfaceBelow(x, z), "rug") << x << ", " << z;
  for (double x : {-1.9, -1.2, 1.5}) EXPECT_EQ(surfaceBelow(x, 0.3), "floor_again") << x;
}

TEST(ReferenceTest, FurnaceIsExactAtEveryPoint) {
  const Scene base = loadScene(kScenes + "furnace.json");
  int beyond = 0;
  for (double rho : {0.5, 0.9}) {
    const Scene scene = withReflectance(base, rho);
    const TraceScene traced(scene);
    const auto points = gridPoints(traced, {0.002, 0.5, 0.97});
    ASSERT_EQ(points.size(), 6u * 9u);
    TraceOptions options;
    options.paths = 4096;
    const auto estimates = PathTracer(traced).estimate(points, options);
    for (size_t i = 0; i < points.size(); ++i)
      beyond += outside(glm::dvec3(1 / (1 - rho)), estimates[i], points[i].position) > 0;
  }
  EXPECT_LE(beyond, 2);
}

/// The scene's emitter: its emission E and the outline of its first polygon.
glm::dvec3 emitterOf(const Scene& scene, std::vector<glm::dvec3>& outline) {
  glm::dvec3 E(0.0);
  for (const auto& s : scene.surfaces) {
    const Material& m = scene.materials[size_t(s.material)];
    if (m.emits()) E = m.emission, outline = s.polygons[0].outer;
  }
  return E;
}

/// Gives `surface` a material of its own reflecting rho.
void makeReceiver(Scene& scene, int surface, const glm::dvec3& rho) {
  Material receiver;
  receiver.name = "receiver";
  receiver.reflectance = rho;
  scene.materials.push_back(receiver);
  scene.surfaces[size_t(surface)].material = int(scene.materials.size() - 1);
}

/// The empty Cornell box with every reflectance 0 but the receivers': B = ρ·E·F, F the exact
/// unoccluded factor from the point to the light (cornell_box.md lists four on the floor).
TEST(ReferenceTest, DirectLightIsRhoEF) {
  const Scene empty = withReflectance(loadScene(kScenes + "cornell_empty.json"), 0);
  const glm::dvec3 rho(0.725, 0.71, 0.68);
  struct Case { glm::dvec3 p, n; double F; };
  const glm::dvec3 up(0, 1, 0), back(0, 0, -1);
  std::vector<Case> cases = {{{278, 0, 279.5}, up, 0.014207}, {{50, 0, 50}, up, 0.0079242},
                             {{500, 0, 500}, up, 0.0081908}, {{100, 0, 400}, up, 0.0107613},
                             {{278, 0.5, 279.5}, up, -1}, {{278, 274, 559.2}, back, -1},
                             {{20, 540, 559.2}, back, -1}, {{540, 3, 559.2}, back, -1}};
  for (const auto& c : cases) {
    // Only the receiving surface reflects: nothing else brings light.
    Scene scene = empty;
    std::vector<glm::dvec3> light;
    const glm::dvec3 E = emitterOf(scene, light);
    const TraceScene traced(scene);
    SurfacePoint q{c.p, c.n, -1, ""};
    if (!locatePoint(traced, q, 1e-6 * traced.size())) {
      EXPECT_EQ(c.p.y, 0.5);  // (278, 0.5, 279.5) lies on no surface
      continue;
    }
    makeReceiver(scene, q.surface, rho);
    const double F = c.F >= 0 ? c.F : pointPolygonFormFactor(c.p, c.n, light);
    EXPECT_NEAR(F, pointPolygonFormFactor(c.p, c.n, light), 1e-6);
    TraceOptions options;
    options.relativeError = 0.005;
    expectWithin(rho * E * F, PathTracer(traced).estimate(q, 0, options), c.p);
  }
}

/// Generalised furnace (oracles.md §4): a closed cube of uniform ρ = 0.5 lit by its ceiling
/// alone (E = 1): the area-weighted mean of B over all faces is Σ A·E / ((1 − ρ) Σ A) = 1/3.
/// Points uniform by area, one path each: the mean is unbiased for the area mean.
TEST(ReferenceTest, GeneralisedFurnaceMean) {
  const double rho = 0.5;
  const Scene scene = withReflectance(loadScene(kScenes + "cube.json"), rho);
  const TraceScene traced(scene);
  const PathTracer tracer(traced);
  const auto& tris = traced.triangles();
  double total = 0, emitted = 0;
  for (const auto& t : tris) total += t.area, emitted += t.area * traced.material(t.surface).emission.x;
  Random rng = Random::stream(7, 0);
  const long n = 400'000;
  double sum = 0, sumSq = 0;
  for (long i = 0; i < n; ++i) {
    double u = rng.next() * total;
    size_t t = 0;
    while (t + 1 < tris.size() && u > tris[t].area) u -= tris[t++].area;
    const double v = rng.next(), w = rng.next();  // one draw each, in a fixed order
    const double b = tracer.tracePath(traced.pointOn(int(t), w, v), tris[t].normal, tris[t].surface, rng).x;
    sum += b, sumSq += b * b;
  }
  const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / (n - 1));
  const double exact = emitted / ((1 - rho) * total);
  EXPECT_NEAR(exact, 1.0 / 3.0, 1e-12);
  EXPECT_LE(std::abs(mean - exact), kSigmas * se) << "mean " << mean << ", SE " << se;
  EXPECT_LT(se / exact, 0.01);
}

/// The standard errors are honest: over many points of exact cases about 68.3 % of the
/// estimates lie within one standard error and 99.7 % within three.
TEST(ReferenceTest, StandardErrorsCoverTheTruth) {
  const Scene scene = withReflectance(loadScene(kScenes + "furnace.json"), 0.5);
  const TraceScene traced(scene);
  std::vector<double> uv;
  for (int i = 0; i < 10; ++i) uv.push_back(0.003 + 0.0994 * i);
  const auto points = gridPoints(traced, uv);  // 600 points
  TraceOptions options;
  options.paths = 2048;
  const auto estimates = PathTracer(traced).estimate(points, options);
  int within1 = 0, within3 = 0, n = 0;
  for (const auto& e : estimates)
    for (int c = 0; c < 3; ++c, ++n) {
      const double z = std::abs(e.B[c] - 2.0) / e.standardError[c];
      within1 += z <= 1;
      within3 += z <= 3;
    }
  // Binomial spread over 1 800 (correlated) channel estimates: a few points either way.
  EXPECT_NEAR(double(within1) / n, 0.683, 0.05) << within1 << " of " << n;
  EXPECT_GE(double(within3) / n, 0.985) << within3 << " of " << n;
}

/// The same seed gives the same numbers, whatever the number of workers.
TEST(ReferenceTest, DeterministicForASeed) {
  const Scene scene = loadScene(kScenes + "cornell.json");
  const TraceScene traced(scene);
  const auto points = placePoints(traced, 12, 3);
  ASSERT_EQ(points.size(), 12u);
  TraceOptions one, two;
  one.paths = two.paths = 2000;
  one.workers = 1, two.workers = 2;
  const auto a = PathTracer(traced).estimate(points, one), b = PathTracer(traced).estimate(points, two);
  for (size_t i = 0; i < points.size(); ++i) EXPECT_EQ(a[i].B, b[i].B);
  EXPECT_EQ(placePoints(traced, 12, 3)[5].position, points[5].position);
}

/// Placed points lie on non-emitting surfaces, never inside the blocks (the floor under them),
/// an eighth near the surfaces' edges and an eighth near contact lines (the blocks' feet among
/// them).
TEST(ReferenceTest, PlacesPointsOnVisibleSurfaces) {
  const Scene scene = loadScene(kScenes + "cornell.json");
  const TraceScene traced(scene);
  const auto points = placePoints(traced, 400, 1);
  ASSERT_EQ(points.size(), 400u);
  int nearEdges = 0, nearContacts = 0, onFloorNearBlocks = 0;
  // The short block's footprint (cornell_box.md): inside it is hidden.
  const std::vector<glm::dvec2> footprint = {{130, 65}, {82, 225}, {240, 272}, {290, 114}};
  for (const auto& p : points) {
    EXPECT_FALSE(traced.material(p.surface).emits());
    nearEdges += p.tag == "edge";
    nearContacts += p.tag == "contact";
    if (scene.surfaces[size_t(p.surface)].name != "floor") continue;
    bool inside = true;
    for (size_t k = 0; k < footprint.size(); ++k) {
      const glm::dvec2 a = footprint[k], b = footprint[(k + 1) % footprint.size()];
      inside &= (b.x - a.x) * (p.position.z - a.y) - (b.y - a.y) * (p.position.x - a.x) < 0;
    }
    EXPECT_FALSE(inside) << "floor point under the short block at " << p.position.x << ", " << p.position.z;
    onFloorNearBlocks += std::abs(p.position.x - 185) < 150 && std::abs(p.position.z - 170) < 150;
  }
  EXPECT_EQ(nearEdges, 50);
  EXPECT_EQ(nearContacts, 50);
  EXPECT_GT(onFloorNearBlocks, 10);
}

}  // namespace
}  // namespace rad::pathtrace

namespace rad {
namespace {

/// The furnace's coarse test settings.
Settings furnaceSettings(const Scene& furnace) {
  SolverBlock flags;
  flags.maxElementEdge = 0.125;
  flags.maxPatchEdge = 0.5;
  flags.tolerance = 1e-3;
  flags.emitterSamples = 4;
  flags.hemicubeResolution = flags.emitterHemicubeResolution = 64;
  return resolveSettings(furnace, flags);
}

/// Points on every face of the furnace, near edges too, located on their surface.
void furnacePoints(const Scene& furnace, const pathtrace::TraceScene& traced,
                   std::vector<pathtrace::SurfacePoint>& points) {
  for (const auto& s : furnace.surfaces) {
    const auto& r = s.polygons[0].outer;
    const glm::dvec3 n = glm::normalize(glm::cross(r[1] - r[0], r[3] - r[0]));
    for (double u : {0.01, 0.3, 0.7})
      for (double v : {0.02, 0.5, 0.95}) {
        pathtrace::SurfacePoint q{r[0] + u * (r[1] - r[0]) + v * (r[3] - r[0]), n, -1, ""};
        ASSERT_TRUE(pathtrace::locatePoint(traced, q, 1e-6));
        points.push_back(q);
      }
  }
}

/// The points with their estimates, as a reference file holds them.
std::vector<ReferencePoint> asReference(const Scene& scene, const std::vector<pathtrace::SurfacePoint>& points,
                                        const std::vector<pathtrace::PointEstimate>& estimates) {
  std::vector<ReferencePoint> out;
  for (size_t i = 0; i < points.size(); ++i)
    out.push_back({points[i].position, points[i].normal, scene.surfaces[size_t(points[i].surface)].name,
                   "", estimates[i].B, estimates[i].standardError, estimates[i].paths});
  return out;
}

/// `solve --reference` on the furnace, whose exact answer (B = 2 everywhere at ρ = 0.5) is
/// known: the true error measured against a path-traced reference agrees with the error
/// against the exact answer to within the reference's own noise.
TEST(TrueErrorTest, MeasuredAgainstTheReferenceAsAgainstTheTruth) {
  const Scene furnace = loadScene(test::kScenes + "furnace.json");
  Settings settings = furnaceSettings(furnace);
  settings.finalGather = false;  // the final gather makes the furnace exact: nothing left to measure
  const MeshedScene m = meshScene(furnace, settings);
  const std::vector<glm::dvec3> shown = shownAtVertices(m, solveRadiosity(m));

  // The reference by path tracing, and the truth.
  const pathtrace::TraceScene traced(furnace);
  std::vector<pathtrace::SurfacePoint> points;
  ASSERT_NO_FATAL_FAILURE(furnacePoints(furnace, traced, points));
  pathtrace::TraceOptions trace;
  trace.paths = 8192;
  const std::vector<ReferencePoint> reference =
      asReference(furnace, points, pathtrace::PathTracer(traced).estimate(points, trace));
  std::vector<ReferencePoint> exact = reference;
  for (ReferencePoint& p : exact) p.B = glm::dvec3(2.0), p.standardError = glm::dvec3(0.0);
  const ErrorSummary measured = TrueError(m.mesh, furnace, reference).measure(shown);
  const ErrorSummary truth = TrueError(m.mesh, furnace, exact).measure(shown);
  EXPECT_EQ(measured.used, 3 * int(points.size()));
  EXPECT_GT(truth.rms, 0.001);  // the solve is not exact: there is an error to measure
  EXPECT_GT(measured.referenceNoise, 0.0);
  EXPECT_LE(std::abs(measured.rms - truth.rms), measured.referenceNoise)
      << "measured " << measured.rms << ", true " << truth.rms << ", reference noise " << measured.referenceNoise;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(measured.meanRgb[c], truth.meanRgb[c], measured.referenceNoise);
}

}  // namespace
}  // namespace rad
