// Uniform against adaptive meshing: error of the displayed (Gouraud) radiosity at points in
// the penumbrae, against element count and run time.
//   build/bin/bench_adaptive [SCENE] [--reference-edge MM] [--points N] [--csv FILE]
//
// The reference at a point x is the direct light computed at x itself by rays to 1 024
// points on each emitter, plus the indirect light of a finer, quieter uniform solution
// (element edge --reference-edge, default 20 mm; hemicubes 256, four points per patch,
// tolerance 1e-4) interpolated at x. The points: random
// points on the non-emitting surfaces (seed 1), kept where the exact direct light is between
// 5 % and 95 % of what it would be without occluders (the penumbrae).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/base/color.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/adaptive.h"
#include "radiosity/formfactors/point_polygon.h"
#include "radiosity/result.h"
#include "radiosity/settings.h"
#include "radiosity/shooting/progressive_solver.h"
#include "radiosity/solve.h"

namespace {

using namespace rad;

constexpr int kReferenceLightSamples = 1024;
constexpr double kPenumbraLow = 0.05, kPenumbraHigh = 0.95;

struct Point {
  glm::dvec3 x{0.0}, normal{0.0}, rho{0.0};
  int surface = -1;
  double direct = 0;  ///< exact direct light, luminance
};

struct Solved {
  MeshedScene meshed;
  std::vector<glm::dvec3> vertexB;  ///< shown at the vertices
  std::vector<glm::dvec3> indirect; ///< at the vertices, without the direct light
  double seconds = 0;
  long shots = 0;
};

Solved solve(const Scene& scene, const Settings& settings) {
  const auto start = std::chrono::steady_clock::now();
  Solved s;
  s.meshed = meshScene(scene, settings);
  RadiositySolve solve(s.meshed);
  while (solve.step()) {
  }
  const Solution solution = solve.bake();
  s.shots = solve.solver().shots();
  s.vertexB = shownAtVertices(s.meshed, solution);
  if (solution.direct) {
    // The display equation without its direct term D.
    VertexDirect none = *solution.direct;
    none.vertex.assign(none.vertex.size(), glm::dvec3(0.0));
    s.indirect = vertexRadiosity(s.meshed.mesh, solution.B, &none);
  }
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

/// The luminance Gouraud shading shows at x (NaN where no element of `elements` has it).
double shownAt(const PatchMesh& mesh, const std::vector<int>& elements,
               const std::vector<glm::dvec3>& vertexValue, const glm::dvec3& x) {
  const auto value = gouraudAt(mesh, elements, vertexValue, x);
  return value ? luminance(*value) : NAN;
}

std::vector<std::vector<int>> frontElementsBySurface(const PatchMesh& mesh, size_t surfaces) {
  std::vector<std::vector<int>> out(surfaces);
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (mesh.side(e) == 0) out[size_t(mesh.surface(e))].push_back(e);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenePath = std::string(RAD_SOURCE_DIR) + "/scenes/cornell.json", csv;
  double referenceEdge = 20;
  int wanted = 2000;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--reference-edge") && i + 1 < argc) referenceEdge = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--points") && i + 1 < argc) wanted = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else scenePath = argv[i];
  }
  const Scene scene = loadScene(scenePath);
  const Settings defaults = resolveSettings(scene, SolverBlock{});

  // The reference solution and the points.
  Settings refSettings = defaults;
  refSettings.adaptive = false;
  refSettings.maxElementEdge = referenceEdge;
  refSettings.maxPatchEdge = 3 * referenceEdge;
  // Less hemicube noise than any case measured: finer hemicubes, four points on every patch,
  // ten times tighter convergence (between seeds, 0.55 % L2 apart at element edge 27.5).
  refSettings.hemicubeResolution = 256;
  refSettings.shooterSamples = 4;
  refSettings.tolerance = 1e-4;
  std::fprintf(stderr, "reference: uniform, element edge %g ...\n", referenceEdge);
  Solved reference = solve(scene, refSettings);
  const PatchMesh& refMesh = reference.meshed.mesh;
  std::fprintf(stderr, "reference: %d elements, %.1f s\n", refMesh.elementCount(), reference.seconds);
  DirectLight exact(refMesh, scene.diagonal(), kReferenceLightSamples, kReferenceLightSamples);
  const auto refElements = frontElementsBySurface(refMesh, scene.surfaces.size());

  std::mt19937_64 random(1);
  std::vector<double> cumulative;
  std::vector<int> candidates;
  double total = 0;
  for (int e = 0; e < refMesh.elementCount(); ++e) {
    if (refMesh.side(e) != 0 || luminance(refMesh.emission(e)) > 0) continue;
    if (refMesh.reflectance(e) == glm::dvec3(0.0)) continue;
    total += refMesh.area(e);
    cumulative.push_back(total);
    candidates.push_back(e);
  }
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Point> points;
  for (int tries = 0; int(points.size()) < wanted && tries < 400 * wanted; tries += 256) {
    std::vector<DirectLight::Probe> probes;
    std::vector<Point> batch;
    for (int k = 0; k < 256; ++k) {
      const size_t i = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), uniform(random) * total) - cumulative.begin());
      const int e = candidates[std::min(i, candidates.size() - 1)];
      const auto c = refMesh.corners(e);
      double u = uniform(random), v = uniform(random);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      Point p;
      p.x = c[0] + (c[1] - c[0]) * u + (c[2] - c[0]) * v;
      p.normal = refMesh.normal(e);
      p.rho = refMesh.reflectance(e);
      p.surface = refMesh.surface(e);
      batch.push_back(p);
      probes.push_back({p.x, p.normal, p.rho, refMesh.centroid(e) - p.x});
    }
    const auto direct = exact.lightAt(probes);
    for (size_t k = 0; k < batch.size(); ++k) {
      double open = 0;
      for (const auto& t : exact.lights())
        if (glm::dot(t.normal, batch[k].x - t.outlines[0][0]) > 0)
          open += luminance(batch[k].rho * t.emission) *
                  pointRegionFormFactor(batch[k].x, batch[k].normal, t.outlines);
      batch[k].direct = luminance(direct[k].radiosity);
      if (open > 0 && batch[k].direct > kPenumbraLow * open && batch[k].direct < kPenumbraHigh * open &&
          int(points.size()) < wanted)
        points.push_back(batch[k]);
    }
  }
  std::vector<double> truth, truthIndirect;
  for (const auto& p : points) {
    const double indirect = shownAt(refMesh, refElements[size_t(p.surface)], reference.indirect, p.x);
    truthIndirect.push_back(std::isnan(indirect) ? 0.0 : indirect);
    truth.push_back(p.direct + truthIndirect.back());
  }
  std::fprintf(stderr, "%zu penumbra points\n", points.size());

  struct Case {
    const char* name;
    bool adaptive, vertexDirect;
    double edge, minEdge, contrast;
  };
  const double base = defaults.maxElementEdge;
  std::vector<Case> cases = {
      {"uniform, hemicube direct", false, false, base, 0, 0},
      {"uniform", false, true, base, 0, 0},
      {"uniform", false, true, base / 1.5, 0, 0},
      {"uniform", false, true, base / 2, 0, 0},
      {"uniform", false, true, base / 3, 0, 0},
      {"uniform", false, true, base / 4, 0, 0},
      {"uniform", false, true, base / 5.5, 0, 0},
      {"adaptive", true, true, base, base / 4, 0.04},
      {"adaptive", true, true, base, base / 4, 0.02},
      {"adaptive", true, true, base, base / 8, 0.04},
      {"adaptive", true, true, base, base / 8, 0.02},
      {"adaptive", true, true, base, base / 8, 0.01},
  };
  FILE* out = csv.empty() ? nullptr : std::fopen(csv.c_str(), "w");
  if (out) std::fprintf(out, "mesh,element_edge,min_element_edge,contrast,elements,seconds,l2_error,mean_abs_error\n");
  std::printf("| mesh | element edge | min edge | contrast | elements | seconds | L2 error | mean abs error | of which direct | of which indirect |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Case& c : cases) {
    Settings s = defaults;
    s.adaptive = c.adaptive;
    s.vertexDirect = c.vertexDirect;
    s.maxElementEdge = c.edge;
    s.maxPatchEdge = defaults.maxPatchEdge;
    s.minElementEdge = c.minEdge;
    s.contrast = c.contrast > 0 ? c.contrast : s.contrast;
    Solved solved = solve(scene, s);
    const auto elements = frontElementsBySurface(solved.meshed.mesh, scene.surfaces.size());
    double sq = 0, ref = 0, abs = 0, meanRef = 0, directAbs = 0, indirectAbs = 0;
    int n = 0;
    for (size_t k = 0; k < points.size(); ++k) {
      const auto& where = elements[size_t(points[k].surface)];
      const double shown = shownAt(solved.meshed.mesh, where, solved.vertexB, points[k].x);
      if (std::isnan(shown)) continue;
      if (!solved.indirect.empty()) {
        const double indirect = shownAt(solved.meshed.mesh, where, solved.indirect, points[k].x);
        indirectAbs += std::abs(indirect - truthIndirect[k]);
        directAbs += std::abs(shown - indirect - points[k].direct);
      }
      sq += (shown - truth[k]) * (shown - truth[k]);
      ref += truth[k] * truth[k];
      abs += std::abs(shown - truth[k]);
      meanRef += truth[k];
      ++n;
    }
    const double l2 = std::sqrt(sq / ref), meanAbs = abs / meanRef;
    std::printf("| %s | %.3g | %s | %s | %d | %.2f | %.2f %% | %.2f %% | %.2f %% | %.2f %% |\n", c.name, c.edge,
                c.adaptive ? std::to_string(c.minEdge).substr(0, 5).c_str() : "–",
                c.adaptive ? std::to_string(c.contrast).substr(0, 4).c_str() : "–",
                solved.meshed.mesh.elementCount(), solved.seconds, 100 * l2, 100 * meanAbs,
                100 * directAbs / meanRef, 100 * indirectAbs / meanRef);
    std::fflush(stdout);
    if (out)
      std::fprintf(out, "%s,%g,%g,%g,%d,%g,%g,%g\n", c.name, c.edge, c.adaptive ? c.minEdge : 0.0,
                   c.adaptive ? c.contrast : 0.0, solved.meshed.mesh.elementCount(), solved.seconds, l2, meanAbs);
    if (n < int(points.size())) std::fprintf(stderr, "  (%d of %zu points located)\n", n, points.size());
  }
  if (out) std::fclose(out);
  return 0;
}
