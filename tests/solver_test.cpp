// Progressive refinement against the closed forms of oracles.md §4 and the identities of §5.
#include <cmath>
#include <map>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/refine.h"
#include "mesh/results/result_file.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/formfactors/point_polygon.h"
#include "radiosity/reference_solver.h"
#include "radiosity/result.h"
#include "radiosity/settings.h"
#include "radiosity/shooting/progressive_solver.h"
#include "tests/support.h"

namespace rad {
namespace {

using test::kScenes;

/// The tables of oracles.md §4 are given to 1e-9; a converged solve matches them to this.
constexpr double kTable = 1e-6;
/// The ledger closes to round-off relative to the power shot.
constexpr double kLedger = 1e-9;
/// Light escaping a closed box, of what was emitted: round-off only.
constexpr double kLeak = 1e-9;

/// Exact factors injected per surface: F[from surface][to surface], shared among the target
/// surface's elements by area.
class SurfaceFactors : public FactorSource {
 public:
  SurfaceFactors(const PatchMesh& mesh, std::vector<std::vector<double>> F) : mesh_(mesh), F_(std::move(F)) {
    area_.assign(F_.size(), 0.0);
    for (int e = 0; e < mesh.elementCount(); ++e) area_[mesh.surface(e)] += mesh.area(e);
  }
  void factors(const Shooter& shooter, int, const ShooterSample&, FormFactors& out, int) override {
    int from = mesh_.patches[shooter.patch].surface;
    out.elements.clear();
    out.factors.clear();
    double sum = 0;
    for (int e = 0; e < mesh_.elementCount(); ++e) {
      double f = F_[from][mesh_.surface(e)] * mesh_.area(e) / area_[mesh_.surface(e)];
      if (f == 0) continue;
      out.elements.push_back(e);
      out.factors.push_back(f);
      sum += f;
    }
    out.sky = 1 - sum;
    out.backFaces = 0;
  }

 private:
  const PatchMesh& mesh_;
  std::vector<std::vector<double>> F_;
  std::vector<double> area_;
};

/// A scene with every material's reflectance set to rho (and the emitter's too, unless
/// emitterRho >= 0), meshed coarsely: one patch per face.
PatchMesh coarseMesh(Scene& scene, double rho, double emitterRho = -1) {
  for (auto& m : scene.materials) {
    m.reflectance = glm::dvec3(m.emits() && emitterRho >= 0 ? emitterRho : rho);
  }
  return buildPatchMesh(scene, {10, 10});
}

/// Mean radiosity (red channel) per surface.
std::vector<double> surfaceMeans(const PatchMesh& mesh, const std::vector<glm::dvec3>& B) {
  std::vector<double> sum(mesh.surfaces.size(), 0.0), area(mesh.surfaces.size(), 0.0);
  for (int e = 0; e < mesh.elementCount(); ++e) {
    sum[mesh.surface(e)] += mesh.area(e) * B[e].x;
    area[mesh.surface(e)] += mesh.area(e);
  }
  for (size_t s = 0; s < sum.size(); ++s) sum[s] /= area[s];
  return sum;
}

SolverOptions converged() {
  SolverOptions o;
  o.tolerance = 1e-12;
  o.emitterSamples = o.shooterSamples = 1;
  return o;
}

struct CubeRow {
  double rho, emitterRho, ceiling, floor, wall;
};

TEST(SolverTest, ClosedUnitCubeWithExactFactorsMatchesTheTable) {
  const double Fopp = 0.1998248957, Fadj = (1 - Fopp) / 4;
  const CubeRow rows[] = {{0.5, -1, 1.090909098, 0.181745826, 0.181836269},
                          {0.8, -1, 1.551724154, 0.689551071, 0.689681194},
                          {0.9, -1, 2.372881375, 1.525310551, 1.525452019},
                          {0.5, 0, 1, 0.166600339, 0.166683245},
                          {0.8, 0, 1, 0.444377352, 0.444461209},
                          {0.9, 0, 1, 0.642809441, 0.642869060}};
  for (const auto& row : rows) {
    Scene scene = loadScene(kScenes + "cube.json");
    PatchMesh mesh = coarseMesh(scene, row.rho, row.emitterRho);
    // Surfaces in cube.json: floor, ceiling, wall_x0, wall_x1, wall_z0, wall_z1.
    std::vector<std::vector<double>> F(6, std::vector<double>(6, Fadj));
    for (int s = 0; s < 6; ++s) F[s][s] = 0;
    F[0][1] = F[1][0] = F[2][3] = F[3][2] = F[4][5] = F[5][4] = Fopp;
    SurfaceFactors factors(mesh, F);
    ProgressiveSolver solver(mesh, factors, converged());
    solver.run();
    auto B = surfaceMeans(mesh, solver.radiosity());
    EXPECT_NEAR(B[1], row.ceiling, kTable) << "rho " << row.rho;
    EXPECT_NEAR(B[0], row.floor, kTable) << "rho " << row.rho;
    for (int s = 2; s < 6; ++s) EXPECT_NEAR(B[s], row.wall, kTable) << "rho " << row.rho;
    EXPECT_EQ(solver.stopReason(), ProgressiveSolver::Stop::Tolerance);
  }
}

TEST(SolverTest, TwoPlatesMatchTheClosedForm) {
  Scene scene = loadScene(kScenes + "parallel_squares.json");  // bottom emits 1, rho 0.8 both
  for (auto& m : scene.materials) m.reflectance = glm::dvec3(0.9);
  PatchMesh mesh = buildPatchMesh(scene, {10, 10});
  // Infinite parallel plates: every factor between them is 1.
  SurfaceFactors plates(mesh, {{0, 1}, {1, 0}});
  ProgressiveSolver solver(mesh, plates, converged());
  solver.run();
  auto B = surfaceMeans(mesh, solver.radiosity());
  EXPECT_NEAR(B[0], 5.263158, kTable);
  EXPECT_NEAR(B[1], 4.736842, kTable);

  // Two unit squares one apart, rho = 0.8.
  for (auto& m : scene.materials) m.reflectance = glm::dvec3(0.8);
  PatchMesh squares = buildPatchMesh(scene, {10, 10});
  SurfaceFactors apart(squares, {{0, 0.1998249}, {0.1998249, 0}});
  ProgressiveSolver solver2(squares, apart, converged());
  solver2.run();
  B = surfaceMeans(squares, solver2.radiosity());
  EXPECT_NEAR(B[0], 1.026225, kTable);
  EXPECT_NEAR(B[1], 0.164052, kTable);
}

/// The Cornell box with hemicube factors, shot by shot.
class CornellSolveTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = loadScene(kScenes + "cornell.json");
    mesh_ = buildPatchMesh(scene_, {80, 160});
  }
  Scene scene_;
  PatchMesh mesh_;
};

TEST_F(CornellSolveTest, LedgerBalancesAfterEveryShotAndUnshotNeverGrows) {
  HemicubeFactors factors(mesh_, 64, scene_.diagonal(), 1);
  SolverOptions options;
  options.maxShots = 300;
  ProgressiveSolver solver(mesh_, factors, options);
  double lastUnshot = solver.unshotFraction();
  while (solver.step()) {
    const EnergyLedger& l = solver.ledger();
    glm::dvec3 gap = l.emitted - l.absorbed - l.escaped - l.unshot;
    for (int k = 0; k < 3; ++k)
      ASSERT_LE(std::abs(gap[k]), kLedger * solver.powerShot()) << "shot " << solver.shots();
    ASSERT_LE(solver.unshotFraction(), lastUnshot * (1 + 1e-12)) << "shot " << solver.shots();
    lastUnshot = solver.unshotFraction();
    for (const auto& b : solver.radiosity())
      ASSERT_TRUE(b.x >= 0 && b.y >= 0 && b.z >= 0 && std::isfinite(b.x + b.y + b.z));
  }
  // The open front lets a good share of the light escape (cornell_box.md: 28-35 %).
  const EnergyLedger& l = solver.ledger();
  double escaped = luminance(l.escaped) / luminance(l.emitted);
  EXPECT_GT(escaped, 0.2);
  EXPECT_LT(escaped, 0.4);
}

TEST_F(CornellSolveTest, DoublingEmissionDoublesRadiosity) {
  HemicubeFactors factors(mesh_, 64, scene_.diagonal(), 1);
  SolverOptions options;
  options.maxShots = 60;
  ProgressiveSolver once(mesh_, factors, options);
  once.run();
  PatchMesh doubled = mesh_;
  for (int e = 0; e < doubled.elementCount(); ++e)
    doubled.setElement(e, doubled.surface(e), doubled.side(e), doubled.area(e),
                       doubled.reflectance(e), 2.0 * doubled.emission(e), doubled.normal(e));
  HemicubeFactors factors2(doubled, 64, scene_.diagonal(), 1);
  ProgressiveSolver twice(doubled, factors2, options);
  twice.run();
  for (int e = 0; e < mesh_.elementCount(); ++e)
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(twice.radiosity()[e][k], 2 * once.radiosity()[e][k],
                  1e-12 * std::abs(once.radiosity()[e][k]) + 1e-300);
}


/// Progressive refinement, Jacobi and Gauss–Seidel all converge to the LU solution of the
/// system built from the very same hemicubes.
/// On the coloured Cornell box and on the grey cube (where the progressive and LU solvers
/// carry one channel and copy it, while Jacobi and Gauss–Seidel carry all three).
TEST(ReferenceTest, EverySolverConvergesToTheLUSolutionOnTheSameFactors) {
  const struct {
    const char* scene;
    double element, patch;
    bool grey;
  } cases[] = {{"cornell.json", 110, 220, false}, {"cube.json", 0.3, 0.6, true}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.scene);
    Scene scene = loadScene(kScenes + c.scene);
    PatchMesh mesh = buildPatchMesh(scene, {c.element, c.patch});
    EXPECT_EQ(isGrey(mesh), c.grey);
    HemicubeFactors factors(mesh, 64, scene.diagonal(), 3);
    SolverOptions options;
    options.tolerance = 1e-10;
    options.clusters = false;  // the very same factors: every patch shoots alone
    TransportMatrix system(mesh, factors, options);
    std::vector<glm::dvec3> byLU = system.solveByLU();

    ProgressiveSolver progressive(mesh, factors, options);
    progressive.run();
    EXPECT_EQ(progressive.grey(), c.grey);
    EXPECT_LT(relativeError(mesh, progressive.radiosity(), byLU), 1e-8);

    double jacobi = 1, gaussSeidel = 1;
    system.solveJacobi(400, [&](int, const std::vector<glm::dvec3>& B) {
      jacobi = relativeError(mesh, B, byLU);
      return jacobi > 1e-10;
    });
    system.solveGaussSeidel(400, [&](int, const std::vector<glm::dvec3>& B) {
      gaussSeidel = relativeError(mesh, B, byLU);
      return gaussSeidel > 1e-10;
    });
    EXPECT_LT(jacobi, 1e-9);
    EXPECT_LT(gaussSeidel, 1e-9);
    for (const auto& b : byLU) EXPECT_TRUE(b.x >= 0 && b.y >= 0 && b.z >= 0);
  }
}

TEST(ReferenceTest, RelativeErrorIgnoresEmittersAndWeighsByArea) {
  Scene scene = loadScene(kScenes + "parallel_squares.json");
  PatchMesh mesh = buildPatchMesh(scene, {10, 10});
  std::vector<glm::dvec3> ref(mesh.elementCount(), glm::dvec3(1.0)), B(ref);
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (mesh.surface(e) == 0) B[e] = glm::dvec3(5.0);  // the emitter: not counted
  EXPECT_EQ(relativeError(mesh, B, ref), 0.0);
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (mesh.surface(e) == 1) B[e] = glm::dvec3(1.1);
  EXPECT_NEAR(relativeError(mesh, B, ref), 0.1, 1e-12);
}


/// Scaling the geometry and every length setting by a power of two scales every floating-point
/// quantity exactly, so radiosities must not move: a difference reveals an absolute tolerance.
TEST(ScaleTest, RadiosityIsScaleInvariant) {
  auto solve = [](double s) {
    Scene scene = loadScene(kScenes + "cornell.json");
    for (auto& surface : scene.surfaces)
      for (auto& polygon : surface.polygons) {
        for (auto& p : polygon.outer) p *= s;
        for (auto& hole : polygon.holes)
          for (auto& p : hole) p *= s;
      }
    PatchMesh mesh = buildPatchMesh(scene, {100 * s, 200 * s});
    HemicubeFactors factors(mesh, 64, scene.diagonal(), 1);
    SolverOptions options;
    options.maxShots = 150;
    ProgressiveSolver solver(mesh, factors, options);
    solver.run();
    return solver.radiosity();
  };
  auto unit = solve(1);
  for (double s : {std::ldexp(1.0, 10), std::ldexp(1.0, -10)}) {
    auto scaled = solve(s);
    ASSERT_EQ(scaled.size(), unit.size());
    for (size_t e = 0; e < unit.size(); ++e)
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(scaled[e][k], unit[e][k], 1e-6 * std::abs(unit[e][k]) + 1e-300)
            << "scale " << s << ", element " << e;
  }
}


/// scenes/penumbra.json: a 100×100 light 200 above the floor, a black square 100 above it,
/// here 40×40 (the file's is 60×60). The exact direct factor from a floor point x is the
/// light's minus that of the part of it the square hides, which is the light ∩ the square
/// projected from x (scale 2): no umbra; a penumbra out to |x| or |z| = 90.
constexpr double kBlockerHalf = 20;
double visibleLightFactor(const glm::dvec3& x) {
  auto rect = [](double x0, double x1, double z0, double z1) {
    return std::vector<glm::dvec3>{{x0, 200, z0}, {x1, 200, z0}, {x1, 200, z1}, {x0, 200, z1}};
  };
  const glm::dvec3 up(0, 1, 0);
  double f = pointPolygonFormFactor(x, up, rect(-50, 50, -50, 50));
  const double h = 2 * kBlockerHalf;
  double x0 = std::max(-50.0, -h - x.x), x1 = std::min(50.0, h - x.x);
  double z0 = std::max(-50.0, -h - x.z), z1 = std::min(50.0, h - x.z);
  if (x0 < x1 && z0 < z1) f -= pointPolygonFormFactor(x, up, rect(x0, x1, z0, z1));
  return f;
}

TEST(PenumbraTest, SoftShadowMatchesTheExactVisibleFactor) {
  Scene scene = loadScene(kScenes + "penumbra.json");
  for (auto& s : scene.surfaces)
    if (s.name == "blocker")
      for (auto& p : s.polygons[0].outer) p.x = std::copysign(kBlockerHalf, p.x), p.z = std::copysign(kBlockerHalf, p.z);
  Settings settings = resolveSettings(scene, SolverBlock{});
  PatchMesh mesh = buildPatchMesh(scene, settings.mesh());
  HemicubeFactors factors(mesh, settings.hemicubeResolution, scene.diagonal(), settings.seed);
  SolverOptions options;
  options.emitterSamples = settings.emitterSamples;
  ProgressiveSolver solver(mesh, factors, options);
  solver.run();  // only the light has power to shoot: the rest is black or sees nothing
  // The displayed (Gouraud) radiosity at floor vertices along the line z = 0 across the shadow.
  std::vector<glm::dvec3> vertexB = vertexRadiosity(mesh, solver.radiosity());
  const double rho = 0.5, L = settings.maxElementEdge;
  const std::vector<glm::dvec3> light = {{-50, 200, -50}, {50, 200, -50}, {50, 200, 50}, {-50, 200, 50}};
  std::vector<std::pair<double, double>> solved, exact;  // (x, B / B unoccluded)
  int compared = 0;
  for (auto v : mesh.mesh.vertices()) {
    glm::dvec3 p = PatchMesh::toGlm(mesh.mesh.point(v));
    auto f = *mesh.mesh.vf_range(v).begin();
    if (scene.surfaces[mesh.surface(f.idx())].name != "floor") continue;
    if (std::abs(p.z) > L || std::abs(p.x) > 140) continue;
    double expected = rho * visibleLightFactor(p);
    double open = rho * pointPolygonFormFactor(p, {0, 1, 0}, light);
    double B = vertexB[v.idx()].x;
    solved.push_back({p.x, B / open});
    exact.push_back({p.x, expected / open});
    if (expected > 0.2 * open) {
      EXPECT_NEAR(B / expected, 1.0, 0.05) << "at x = " << p.x << ", z = " << p.z;
      ++compared;
    }
  }
  EXPECT_GT(compared, 20);
  // Where the penumbra reaches three quarters of the full light: as similar triangles put it,
  // within two elements.
  auto crossing = [](std::vector<std::pair<double, double>> v) {
    std::sort(v.begin(), v.end());
    double at = 0;
    for (size_t i = 0; i + 1 < v.size(); ++i)
      if (v[i].first > 0 && v[i].second < 0.75 && v[i + 1].second >= 0.75) at = v[i].first;
    return at;
  };
  double xs = crossing(solved), xe = crossing(exact);
  EXPECT_GT(xe, 20);
  EXPECT_NEAR(xs, xe, 2 * L);
  // Beyond x = 90 (light edge, past the square's edge, to the floor) the whole light is seen.
  for (const auto& [x, ratio] : solved)
    if (std::abs(x) > 90 + 2 * L) {
      EXPECT_NEAR(ratio, 1.0, 0.05) << "at x = " << x;
    }
}


/// Kept factors are the factors a hemicube would render again (same point, same rotation):
/// the solution is bit for bit the same with or without the cache, for far fewer hemicubes;
/// a budget too small for every row keeps some and renders the rest again.
TEST(FactorCacheTest, SameResultWithFewerHemicubes) {
  Scene scene = loadScene(kScenes + "cornell.json");
  PatchMesh mesh = buildPatchMesh(scene, {110, 220});
  HemicubeFactors factors(mesh, 64, scene.diagonal(), 5);
  std::vector<std::vector<glm::dvec3>> results;
  std::vector<long> hemicubes;
  for (size_t budget : {size_t(0), size_t(200) << 10, size_t(256) << 20}) {
    SolverOptions options;
    options.maxShots = 400;
    options.factorCacheBytes = budget;
    ProgressiveSolver solver(mesh, factors, options);
    solver.run();
    EXPECT_LE(solver.cachedBytes(), budget);
    results.push_back(solver.radiosity());
    hemicubes.push_back(solver.hemicubes());
  }
  EXPECT_EQ(results[0], results[1]);
  EXPECT_EQ(results[0], results[2]);
  EXPECT_GT(hemicubes[0], hemicubes[1]);
  EXPECT_GT(hemicubes[1], hemicubes[2]);
  EXPECT_LT(3 * hemicubes[2], hemicubes[0]);  // a patch shoots several times
}

/// Emitters shoot from emitterSamples points; other patches from shooterSamples, more the
/// nearer they are to a facing surface: (D/d)² grows with proximity.
TEST(SamplesTest, MorePointsNearOtherSurfaces) {
  Scene scene = loadScene(kScenes + "cornell.json");
  PatchMesh mesh = buildPatchMesh(scene, {50, 150});
  SolverOptions options;
  options.shooterSamples = 1;
  options.proximitySamples = 0.7;
  const SampleCounter counter(mesh, options);
  int nearCorner = 0, midWall = 0, lights = 0;
  for (int p = 0; p < int(mesh.patches.size()); ++p) {
    const Patch& patch = mesh.patches[p];
    int count = counter(p);
    EXPECT_GE(count, options.shooterSamples);
    EXPECT_LE(count, options.emitterSamples);
    if (luminance(mesh.emission(patch.elements[0])) > 0) {
      EXPECT_EQ(count, options.emitterSamples);
      ++lights;
      continue;
    }
    if (scene.surfaces[patch.surface].name != "back_wall") continue;
    // The back wall spans x, y in [0, 556]: patches at a corner touch two other walls.
    const glm::dvec3& c = patch.centroid;
    double edgeDistance = std::min({c.x, 556 - c.x, c.y, 549 - c.y});
    if (edgeDistance < 60) nearCorner = std::max(nearCorner, count);
    if (edgeDistance > 200) midWall = std::max(midWall, count);
  }
  EXPECT_GT(lights, 0);
  EXPECT_GE(nearCorner, 4);
  EXPECT_LE(midWall, 2);
  options.proximitySamples = 0;
  const SampleCounter fixed(mesh, options);
  for (int p = 0; p < int(mesh.patches.size()); p += 5)
    if (luminance(mesh.emission(mesh.patches[p].elements[0])) == 0) {
      EXPECT_EQ(fixed(p), 1);
    }
  // A minimum above the emitters' count wins (no clamp with crossed bounds).
  options.proximitySamples = 0.7;
  options.shooterSamples = 8;
  options.emitterSamples = 2;
  const SampleCounter crossed(mesh, options);
  for (int p = 0; p < int(mesh.patches.size()); p += 5)
    if (luminance(mesh.emission(mesh.patches[p].elements[0])) == 0) {
      EXPECT_EQ(crossed(p), 8);
    }
}

TEST(DeterminismTest, SameResultWithOneOrTwoWorkers) {
  Scene scene = loadScene(kScenes + "cornell.json");
  PatchMesh mesh = buildPatchMesh(scene, {110, 220});
  SolverOptions options;
  options.maxShots = 80;
  std::vector<std::vector<glm::dvec3>> results;
  for (int workers : {1, 2}) {
    HemicubeFactors factors(mesh, 64, scene.diagonal(), 5, workers);
    ProgressiveSolver solver(mesh, factors, options);
    solver.run();
    results.push_back(solver.radiosity());
  }
  EXPECT_EQ(results[0], results[1]);
}


/// Generalised furnace (oracles.md §4): closed, uniform ρ, any emission →
/// Σ A·B = Σ A·E / (1 − ρ), per channel; hemicube rows that leak would break it.
TEST(FurnaceTest, GeneralisedFurnaceHoldsOnHemicubeFactors) {
  for (double rho : {0.5, 0.9}) {
    Scene scene = loadScene(kScenes + "cube.json");  // only the ceiling emits
    for (auto& m : scene.materials) m.reflectance = glm::dvec3(rho);
    PatchMesh mesh = buildPatchMesh(scene, {0.4, 0.4});
    HemicubeFactors factors(mesh, 64, scene.diagonal(), 1);
    std::vector<glm::dvec3> B = TransportMatrix(mesh, factors, SolverOptions{}).solveByLU();
    glm::dvec3 power(0.0), emitted(0.0);
    for (int e = 0; e < mesh.elementCount(); ++e) {
      power += mesh.area(e) * B[e];
      emitted += mesh.area(e) * mesh.emission(e);
    }
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(power[k] / (emitted[k] / (1 - rho)), 1.0, 1e-6) << "rho " << rho;
  }
}


/// The furnace (oracles.md §4): a closed cube, 4×4 square elements per face (each two
/// triangles; the squares are the patches), uniform ρ and emission E = 1 → B = E/(1−ρ) at
/// every element. Hemicube factors at R = 128 from 64 stratified points per square (as many
/// pixels per square as 8×8 squares at R = 256, a sixteenth of the hemicubes' work); the
/// system is solved directly on exactly those factors (the progressive solver converges to
/// the same solution: ReferenceTest.EverySolverConvergesToTheLUSolutionOnTheSameFactors). What is left is the
/// proximity error of point-sampled shooters next to the cube's edges.
void furnace(bool refine) {
  constexpr int kGrid = 4;
  constexpr int kSamplesPerSquare = 64;
  constexpr int kResolution = 128;
  Scene scene = loadScene(kScenes + "furnace.json");  // unit cube, E = 1 everywhere
  for (auto& surface : scene.surfaces) {
    Ring q = surface.polygons[0].outer;
    auto at = [&](int i, int j) {
      return q[0] + (q[1] - q[0]) * (double(i) / kGrid) + (q[3] - q[0]) * (double(j) / kGrid);
    };
    surface.polygons.clear();
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j)
        surface.polygons.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, {}});
  }
  const double side = 1.0 / kGrid;
  // Edges up to the square's diagonal: two triangles per square, one patch per square.
  PatchMesh mesh = buildPatchMesh(scene, {side * std::sqrt(2.0) * 1.001, side * std::sqrt(2.0) * 1.001});
  ASSERT_EQ(mesh.elementCount(), 6 * kGrid * kGrid * 2);
  ASSERT_EQ(int(mesh.patches.size()), 6 * kGrid * kGrid);
  if (refine) {
    // Every third element bisected, twice over, as adaptive refinement would.
    for (int round = 0; round < 2; ++round) {
      std::vector<int> some;
      for (int e = 0; e < mesh.elementCount(); e += 3) some.push_back(e);
      bisectElements(mesh, some);
    }
    ASSERT_GT(mesh.elementCount(), 2 * 6 * kGrid * kGrid * 2);
    ASSERT_TRUE(findTJunctions(mesh, 1e-7, true).empty());
  }

  SolverOptions options;
  options.emitterSamples = options.shooterSamples = kSamplesPerSquare;
  HemicubeFactors factors(mesh, kResolution, scene.diagonal(), 1);
  TransportMatrix transport(mesh, factors, options);
  const int n = transport.size();
  // No leak: in the closed cube every hemicube pixel sees an element, so nothing escapes
  // (a crack at a T-junction would let light out).
  {
    SolverOptions shoot = options;
    shoot.maxShots = 200;
    ProgressiveSolver solver(mesh, factors, shoot);
    solver.run();
    EXPECT_LE(luminance(solver.ledger().escaped), kLeak * luminance(solver.ledger().emitted));
  }
  struct Case {
    double rho, tolerance;
  };
  // Refined, the receivers along the cube's edges are down to a sixteenth of a square (the
  // edges are split on both faces that meet there), right beside the adjacent square's 64
  // shooting points: point factors are not reciprocal, less so the smaller the receiver near
  // a shooter (oracles.md, furnace: 2.2 / 4.8 / 5.6 % for element-sized shooters from their
  // centres). Measured 2.3 / 4.3 / 4.8 %; the limits leave a fifth of that for other seeds.
  const std::vector<Case> cases = refine ? std::vector<Case>{{0.5, 0.03}, {0.9, 0.055}, {0.99, 0.06}}
                                         : std::vector<Case>{{0.5, 0.005}, {0.9, 0.01}, {0.99, 0.02}};
  for (const auto& c : cases) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n) - c.rho * transport.G();
    Eigen::VectorXd B = A.partialPivLu().solve(Eigen::VectorXd::Ones(n));
    double worst = 0;
    for (int e = 0; e < n; ++e) worst = std::max(worst, std::abs(B(e) * (1 - c.rho) - 1));
    EXPECT_LE(worst, c.tolerance) << "rho " << c.rho;
    std::printf("furnace%s rho %.2f: worst element off by %.3f %% (%d elements)\n",
                refine ? " refined" : "", c.rho, 100 * worst, n);
  }
}

TEST(FurnaceTest, EveryElementWithinTolerance) { furnace(false); }

/// The same cube with elements bisected the way adaptive refinement does it (conforming):
/// nothing leaks, and the smaller receivers hold the furnace within wider limits.
TEST(FurnaceTest, HoldsAfterRefinement) { furnace(true); }


/// Every element's power is shot exactly once in total (weights sum to 1), from exactly as
/// many points as asked for, each inside one of the patch's elements.
TEST(SamplesTest, StratifiedSamplesCoverEachElementOnce) {
  Scene scene = loadScene(kScenes + "cornell.json");
  PatchMesh mesh = buildPatchMesh(scene, {58, 116});
  auto inside = [&](const glm::dvec3& x, int e) {
    auto c = mesh.corners(e);
    double slack = 1e-9 * scene.diagonal() * scene.diagonal();
    for (int k = 0; k < 3; ++k)
      if (glm::dot(glm::cross(c[(k + 1) % 3] - c[k], x - c[k]), mesh.normal(e)) < -slack) return false;
    return std::abs(glm::dot(x - c[0], mesh.normal(e))) <= 1e-9 * scene.diagonal();
  };
  for (int count : {1, 4, 16, 64}) {
    for (int p = 0; p < int(mesh.patches.size()); p += 7) {
      const Patch& patch = mesh.patches[p];
      auto samples = patchSamples(mesh, p, count);
      EXPECT_EQ(int(samples.size()), count) << "patch " << p;
      std::map<int, double> weight;
      for (const auto& s : samples) {
        for (size_t k = 0; k < s.elements.size(); ++k) weight[s.elements[k]] += s.weights[k];
        bool onPatch = false;
        for (int e : patch.elements) onPatch = onPatch || inside(s.point, e);
        EXPECT_TRUE(onPatch) << "patch " << p << ", " << count << " points";
      }
      ASSERT_EQ(weight.size(), patch.elements.size()) << "patch " << p;
      for (const auto& [e, w] : weight) EXPECT_NEAR(w, 1.0, 1e-12) << "element " << e;
    }
  }
}

}  // namespace

/// A vertex no face uses has no normal and no light: the result file leaves it out, and what it
/// writes reads back as the same elements (OpenMesh gives such a vertex a NaN normal, which
/// the project's own reader refused).
TEST(ResultTest, AVertexNoFaceUsesIsNotWritten) {
  const Scene scene = loadScene(kScenes + "cube.json");
  PatchMesh mesh = buildPatchMesh(scene, {0.5, 0.5});
  const size_t used = mesh.mesh.n_vertices();
  const auto isolated = mesh.mesh.add_vertex(TriMesh::Point(0.5, 0.5, 0.5));
  mesh.mesh.set_normal(isolated, TriMesh::Normal(std::nan(""), std::nan(""), std::nan("")));
  const std::vector<glm::dvec3> B(size_t(mesh.elementCount()), glm::dvec3(0.25));
  const std::string path = ::testing::TempDir() + "isolated_vertex_result.ply";
  writeResult(path, mesh, B, glm::dvec3(0.0), 1.0, Camera{});
  const ResultFile read = readResultFile(path);
  EXPECT_EQ(read.positions.size(), used);
  for (const glm::vec3& n : read.vertexNormal) EXPECT_TRUE(std::isfinite(n.x + n.y + n.z));
  EXPECT_EQ(readResultRadiosity(path, mesh, scene.diagonal()), B);
}

}  // namespace rad
