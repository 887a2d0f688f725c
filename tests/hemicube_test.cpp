// Hemicube and point-to-polygon form factors against the exact answers of oracles.md §1 and §3.
#include <cmath>
#include <functional>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/formfactors/hemicube.h"
#include "radiosity/formfactors/point_polygon.h"
#include "tests/support.h"

namespace rad {
namespace {

using test::kScenes;

/// The oracles are given to six or seven digits.
constexpr double kOracleDigits = 2e-6;
/// The delta form factors' exact integrals must sum to 1 to this.
constexpr double kDeltaSum = 1e-9;
/// Rows of the closed cube sum to 1 to this.
constexpr double kClosure = 1e-6;
constexpr int kRotations = 256;

using Polygon3 = std::vector<glm::dvec3>;

// ---- Lambert's contour formula against closed forms --------------------------------------

/// Parallel rectangle a×b at distance c, the normal through one corner, facing the point.
Polygon3 cornerRectangle(double a, double b, double c) {
  return {{0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c}};
}
/// Perpendicular rectangle in the plane y = c, x in [0, a], z in [0, b], facing the point.
Polygon3 perpendicularRectangle(double a, double b, double c) {
  return {{0, c, 0}, {a, c, 0}, {a, c, b}, {0, c, b}};
}
/// A regular n-gon of radius r in the plane z = h centred at (cx, 0), facing down.
Polygon3 disk(double r, double h, double cx, int n) {
  Polygon3 p;
  for (int k = 0; k < n; ++k) {
    double t = -2 * M_PI * k / n;
    p.emplace_back(cx + r * std::cos(t), r * std::sin(t), h);
  }
  return p;
}
double exactFromOrigin(const Polygon3& p) { return pointPolygonFormFactor({0, 0, 0}, {0, 0, 1}, p); }

TEST(PointPolygonTest, MatchesTheParallelRectangleOracle) {
  EXPECT_NEAR(exactFromOrigin(cornerRectangle(1, 1, 1)), 0.138532, kOracleDigits);
  EXPECT_NEAR(exactFromOrigin(cornerRectangle(0.5, 0.5, 1)), 0.059864, kOracleDigits);
  EXPECT_NEAR(exactFromOrigin(cornerRectangle(2, 1, 1)), 0.167375, kOracleDigits);
  EXPECT_NEAR(exactFromOrigin(cornerRectangle(1, 3, 0.5)), 0.222695, kOracleDigits);
  Polygon3 centred = {{-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}};
  EXPECT_NEAR(exactFromOrigin(centred), 0.2394565, kOracleDigits);
}

TEST(PointPolygonTest, MatchesThePerpendicularRectangleOracle) {
  EXPECT_NEAR(exactFromOrigin(perpendicularRectangle(1, 1, 1)), 0.055734, kOracleDigits);
  EXPECT_NEAR(exactFromOrigin(perpendicularRectangle(2, 1, 0.5)), 0.135488, kOracleDigits);
  EXPECT_NEAR(exactFromOrigin(perpendicularRectangle(1, 2, 1)), 0.095068, kOracleDigits);
  EXPECT_NEAR(exactFromOrigin(perpendicularRectangle(1e4, 1e4, 1)), 0.25, 1e-4);
}

TEST(PointPolygonTest, MatchesTheDiskOracles) {
  // A 4096-gon misses a disk's area by 4e-7 relative.
  EXPECT_NEAR(exactFromOrigin(disk(1, 1, 0, 4096)), 0.5, 1e-6);
  EXPECT_NEAR(exactFromOrigin(disk(1, 1, 0.5, 4096)), 0.4379826, 1e-6);
  EXPECT_NEAR(exactFromOrigin(disk(1, 2, 1.5, 4096)), 0.1022841, 1e-6);
}

TEST(PointPolygonTest, ClipsToTheHemisphereAndIgnoresWinding) {
  // A wall straddling the tangent plane counts only its upper half.
  Polygon3 straddling = {{0, 1, -1}, {0, 1, 1}, {1, 1, 1}, {1, 1, -1}};
  EXPECT_NEAR(exactFromOrigin(straddling), exactFromOrigin(perpendicularRectangle(1, 1, 1)), 1e-12);
  Polygon3 below = {{0, 0, -1}, {1, 0, -1}, {1, 1, -1}};
  EXPECT_EQ(exactFromOrigin(below), 0.0);
  Polygon3 forward = cornerRectangle(1, 1, 1);
  Polygon3 reversed(forward.rbegin(), forward.rend());
  EXPECT_NEAR(exactFromOrigin(reversed), 0.138532, kOracleDigits);
}

// ---- Delta form factors --------------------------------------------------------------------

TEST(DeltaFormFactorsTest, ExactPixelIntegralsSumToOne) {
  for (int R : {16, 64, 256}) {
    const auto& d = DeltaFormFactors::forResolution(R);
    EXPECT_NEAR(d.exactSum, 1.0, kDeltaSum) << "R = " << R;
    double sum = 0;
    for (double f : d.top) sum += f;
    for (double f : d.side) sum += 4 * f;
    EXPECT_NEAR(sum, 1.0, 1e-14);
    // Pixel-centre values (oracles §3) agree with the integrals to O(1/R²) per pixel.
    double dA = (2.0 / R) * (2.0 / R);
    double x = -1 + 1.0 / R, y = -1 + 1.0 / R;  // the corner pixel of the top face
    double centre = dA / (M_PI * std::pow(x * x + y * y + 1, 2));
    EXPECT_NEAR(d.top[0] / centre, 1.0, 2.0 / (R * R)) << "R = " << R;
    double z = 1.0 / R;  // bottom row of a side face: height z above the base
    double side = z * dA / (M_PI * std::pow(x * x + z * z + 1, 2));
    EXPECT_NEAR(d.side[0] / side, 1.0, 4.0 / (R * R) + 1.0 / R) << "R = " << R;
  }
}

// ---- Hemicube against the exact factors, over many rotations --------------------------------

struct ErrorStats {
  double bias = 0, meanAbs = 0;
};

/// Bias and mean |relative error| of the hemicube factor from the origin (normal +z) to the
/// polygon (drawn as a triangle fan), over kRotations deterministic rotations.
ErrorStats hemicubeError(const Polygon3& polygon, int R) {
  HemicubeGeometry g;
  for (size_t k = 1; k + 1 < polygon.size(); ++k) g.addTriangle(polygon[0], polygon[k], polygon[k + 1]);
  double size = 0;
  for (const auto& p : polygon) size = std::max(size, glm::length(p));
  Hemicube hemicube(g, R, size);
  double exact = exactFromOrigin(polygon);
  ErrorStats s;
  FormFactors ff;
  for (int r = 0; r < kRotations; ++r) {
    hemicube.compute({0, 0, 0}, {0, 0, 1}, hemicubeRotation(7, 0, uint64_t(r)), ff);
    double f = 0;
    for (double x : ff.factors) f += x;
    double rel = (f - exact) / exact;
    s.bias += rel / kRotations;
    s.meanAbs += std::abs(rel) / kRotations;
  }
  return s;
}

struct Target {
  std::string name;
  Polygon3 polygon;
  double errorTimesR;  ///< allowed mean |relative error| × R
};

/// The polygons of oracles.md §1 and a few more, each with its allowed mean |error| × R.
std::vector<Target> accuracyTargets() {
  // A non-convex L-shape in a tilted plane, facing the point.
  Polygon3 tilted;
  glm::dvec3 o(-0.3, -0.2, 1.0), e1 = glm::normalize(glm::dvec3(1, 0, 0.3)),
                                 e2 = glm::normalize(glm::dvec3(0, 1, -0.2));
  for (auto [x, y] : std::vector<std::pair<double, double>>{
           {0, 0}, {0, 1}, {0.4, 1}, {0.4, 0.4}, {1, 0.4}, {1, 0}})
    tilted.push_back(o + x * e1 + y * e2);
  return {
      {"corner rectangle 1x1 at 1", cornerRectangle(1, 1, 1), 1.0},
      {"corner rectangle 0.5x0.5 at 1", cornerRectangle(0.5, 0.5, 1), 1.0},
      {"corner rectangle 2x1 at 1", cornerRectangle(2, 1, 1), 1.0},
      {"corner rectangle 1x3 at 0.5", cornerRectangle(1, 3, 0.5), 1.0},
      {"perpendicular rectangle (1,1,1)", perpendicularRectangle(1, 1, 1), 1.0},
      {"perpendicular rectangle (2,1,0.5)", perpendicularRectangle(2, 1, 0.5), 1.0},
      {"perpendicular rectangle (1,2,1)", perpendicularRectangle(1, 2, 1), 1.0},
      {"coaxial disk r=h=1", disk(1, 1, 0, 256), 1.0},
      {"displaced disk (1,1,0.5)", disk(1, 1, 0.5, 256), 1.0},
      {"displaced disk (1,2,1.5)", disk(1, 2, 1.5, 256), 1.0},
      {"tilted non-convex L-shape", tilted, 1.0},
      {"unit square centred at 1", {{-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}}, 0.1},
  };
}

class HemicubeAccuracyTest : public ::testing::TestWithParam<int> {};

TEST_P(HemicubeAccuracyTest, MeanErrorWithinOneOverR) {
  const int R = GetParam();
  for (const auto& t : accuracyTargets()) {
    ErrorStats s = hemicubeError(t.polygon, R);
    EXPECT_LE(s.meanAbs, t.errorTimesR / R)
        << t.name << " at R = " << R << ": mean |error| " << s.meanAbs << ", bias " << s.bias;
    std::printf("  R=%-4d %-36s bias %+.2e  mean|err| %.2e  (limit %.2e)\n", R, t.name.c_str(),
                s.bias, s.meanAbs, t.errorTimesR / R);
  }
}

INSTANTIATE_TEST_SUITE_P(Resolutions, HemicubeAccuracyTest, ::testing::Values(64, 256));

// ---- Hemicubes in meshed scenes --------------------------------------------------------------

struct SceneAndMesh {
  Scene scene;
  PatchMesh mesh;
  HemicubeGeometry geometry;
  int surface(const std::string& name) const {
    for (size_t s = 0; s < scene.surfaces.size(); ++s)
      if (scene.surfaces[s].name == name) return int(s);
    return -1;
  }
  std::vector<double> perSurface(const FormFactors& ff) const {
    std::vector<double> f(scene.surfaces.size(), 0.0);
    for (size_t k = 0; k < ff.elements.size(); ++k) f[mesh.surface(ff.elements[k])] += ff.factors[k];
    return f;
  }
};

SceneAndMesh meshed(const std::string& name, double element, double patch) {
  SceneAndMesh m{loadScene(kScenes + name), {}, {}};
  m.mesh = buildPatchMesh(m.scene, {element, patch});
  m.geometry = HemicubeGeometry::fromMesh(m.mesh);
  return m;
}

TEST(HemicubeSceneTest, ClosedCubeRowsSumToOne) {
  SceneAndMesh m = meshed("cube.json", 0.125, 0.25);
  for (HemicubeCulling culling : {HemicubeCulling::None, HemicubeCulling::Hidden}) {
    Hemicube hemicube(m.geometry, 256, m.scene.diagonal());
    hemicube.setCulling(culling);
    FormFactors ff;
    int tested = 0;
    for (int e = 0; e < m.mesh.elementCount(); e += 37, ++tested) {
      hemicube.compute(m.mesh.centroid(e), m.mesh.normal(e), hemicubeRotation(1, e, 0), ff, {e});
      double sum = 0;
      for (double f : ff.factors) sum += f;
      EXPECT_NEAR(sum, 1.0, kClosure) << "element " << e << ", culling " << int(culling) << ": sky " << ff.sky
                                      << ", back " << ff.backFaces;
    }
    EXPECT_GT(tested, 20);
  }
}

TEST(HemicubeSceneTest, OpenCornellBoxFactorsPlusSkyAreOneAndMatchTheLightsOracle) {
  SceneAndMesh m = meshed("cornell_empty.json", 30, 90);
  Hemicube hemicube(m.geometry, 256, m.scene.diagonal());
  FormFactors ff;
  glm::dvec3 lightCentre(278, 548.8 - 1e-9, 279.5);
  hemicube.compute(lightCentre, {0, -1, 0}, hemicubeRotation(1, 0, 0), ff);
  EXPECT_NEAR(ff.sum(), 1.0, 1e-12);
  EXPECT_NEAR(ff.backFaces, 0.0, 1e-12);
  auto f = m.perSurface(ff);
  // cornell_box.md: from the light's centre point (allowing the 1/R aliasing of side faces).
  const double tolerance = 2.0 / 256;
  EXPECT_NEAR(f[m.surface("floor")] / 0.243650, 1.0, tolerance);
  EXPECT_NEAR(f[m.surface("back_wall")] / 0.187123, 1.0, tolerance);
  EXPECT_NEAR(f[m.surface("left_wall")] / 0.192094, 1.0, tolerance);
  EXPECT_NEAR(f[m.surface("right_wall")] / 0.189554, 1.0, tolerance);
  double front = 1 - 0.243650 - 0.187123 - 0.192094 - 0.189554;
  EXPECT_NEAR(ff.sky / front, 1.0, tolerance);
}

TEST(HemicubeSceneTest, NoLightLeaksUnderABlock) {
  SceneAndMesh m = meshed("cornell.json", 30, 90);
  Hemicube hemicube(m.geometry, 256, m.scene.diagonal());
  FormFactors ff;
  int light = m.surface("light");
  for (glm::dvec3 p : {glm::dvec3(186, 0, 169), glm::dvec3(368, 0, 351), glm::dvec3(135, 0, 80)}) {
    hemicube.compute(p, {0, 1, 0}, hemicubeRotation(1, 0, 0), ff);
    EXPECT_EQ(m.perSurface(ff)[light], 0.0) << "at " << p.x << ", " << p.z;
    EXPECT_GT(ff.backFaces, 0.99) << "inside a block only back faces are seen";
  }
  // Beside the block, in the open, the light is seen.
  hemicube.compute({278, 0, 279.5}, {0, 1, 0}, hemicubeRotation(1, 0, 0), ff);
  EXPECT_GT(m.perSurface(ff)[light], 0.0);
}

TEST(HemicubeSceneTest, SameSeedSameFactors) {
  SceneAndMesh m = meshed("cornell.json", 45, 90);
  Hemicube a(m.geometry, 128, m.scene.diagonal()), b(m.geometry, 128, m.scene.diagonal());
  FormFactors fa, fb;
  for (int e : {0, 500, 1000}) {
    a.compute(m.mesh.centroid(e), m.mesh.normal(e), hemicubeRotation(3, e, 0), fa, {e});
    b.compute(m.mesh.centroid(e), m.mesh.normal(e), hemicubeRotation(3, e, 0), fb, {e});
    EXPECT_EQ(fa.elements, fb.elements);
    EXPECT_EQ(fa.factors, fb.factors);
    EXPECT_EQ(fa.sky, fb.sky);
  }
  EXPECT_EQ(hemicubeRotation(3, 10, 2), hemicubeRotation(3, 10, 2));
  EXPECT_NE(hemicubeRotation(3, 10, 2), hemicubeRotation(3, 10, 3));
  EXPECT_NE(hemicubeRotation(3, 10, 2), hemicubeRotation(4, 10, 2));
}

}  // namespace
}  // namespace rad
