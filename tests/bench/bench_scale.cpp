// Cost against size: an interior (Modern Hall, ../shared/scenes/bitterli/staircase2, by
// default) with its mesh files' triangles split to a given count, through the shipping
// pipeline at default settings, as `radiosity info` (and with --solve, `radiosity solve`)
// runs it. Prints one CSV row per stage: triangles, elements, vertices, stage, seconds, and
// the process's peak memory (MiB) once the stage is done. Peak memory is the process's, so
// each size runs in a process of its own (tests/bench/scale.sh runs them all).
//
//   bench_scale TRIANGLES [SCENE] [--solve] [--no-gather] [--no-clusters]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mesh/base/error.h"
#include "mesh/base/stage_times.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/settings.h"
#include "radiosity/solve.h"

namespace {

using Clock = rad::StageTimes::Clock;

/// Triangle (a, b, c) split `levels` times into four by its edge midpoints, into `out`.
void split(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int levels, std::vector<rad::Polygon>& out) {
  if (levels == 0) {
    rad::Polygon p;
    p.outer = {a, b, c};
    out.push_back(std::move(p));
    return;
  }
  const glm::dvec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  split(a, ab, ca, levels - 1, out);
  split(ab, b, bc, levels - 1, out);
  split(ca, bc, c, levels - 1, out);
  split(ab, bc, ca, levels - 1, out);
}

/// The mesh files' faces without holes, as fans of triangles: how many.
size_t fileTriangles(const rad::Scene& scene) {
  size_t n = 0;
  for (const rad::Surface& s : scene.surfaces)
    for (const rad::Polygon& p : s.polygons)
      if (s.fromMeshFile && p.holes.empty()) n += p.outer.size() - 2;
  return n;
}

/// Splits the mesh files' triangles so that there are `target` of them: each L times into
/// four, the first ones in file order L + 1 times. Faces with holes are kept as they are.
void splitTo(rad::Scene& scene, size_t target) {
  const size_t base = fileTriangles(scene);
  if (target <= base) return;
  int levels = 0;
  while (double(base) * std::pow(4.0, levels + 1) <= double(target)) ++levels;
  const double atLevel = std::pow(4.0, levels);
  size_t finer = size_t(std::ceil((double(target) - double(base) * atLevel) / (3 * atLevel)));
  for (rad::Surface& s : scene.surfaces) {
    if (!s.fromMeshFile) continue;
    std::vector<rad::Polygon> out;
    for (const rad::Polygon& p : s.polygons) {
      if (!p.holes.empty()) {
        out.push_back(p);
        continue;
      }
      for (size_t k = 1; k + 1 < p.outer.size(); ++k) {
        const int l = levels + (finer > 0 ? 1 : 0);
        if (finer > 0) --finer;
        split(p.outer[0], p.outer[k], p.outer[k + 1], l, out);
      }
    }
    s.polygons = std::move(out);
  }
}

struct Row {
  size_t triangles = 0;
  int elements = 0;
  size_t vertices = 0;

  void print(const std::string& stage, double seconds, double peakMiB = rad::StageTimes::peakMiB()) const {
    std::printf("%zu,%d,%zu,%s,%.3f,%.0f\n", triangles, elements, vertices, stage.c_str(), seconds, peakMiB);
    std::fflush(stdout);
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_scale TRIANGLES [SCENE] [--solve] [--no-gather] [--no-clusters]\n");
    return 2;
  }
  const size_t target = size_t(std::atof(argv[1]));
  std::string path = std::string(RAD_SOURCE_DIR) + "/../shared/scenes/bitterli/staircase2/scene.json";
  bool solve = false;
  rad::SolverBlock flags;  // as the command line's flags
  for (int i = 2; i < argc; ++i) {
    if (std::string(argv[i]) == "--solve")
      solve = true;
    else if (std::string(argv[i]) == "--no-gather")
      flags.finalGather = false;
    else if (std::string(argv[i]) == "--no-clusters")
      flags.clusterShooters = false;
    else
      path = argv[i];
  }
  try {
    auto start = Clock::now();
    rad::Scene scene = rad::loadScene(path);
    splitTo(scene, target);
    Row row;
    row.triangles = fileTriangles(scene);
    const double loading = rad::StageTimes::since(start), loadingPeak = rad::StageTimes::peakMiB();
    start = Clock::now();
    const rad::Settings settings = rad::resolveSettings(scene, flags);
    // As `radiosity solve` meshes: with a solve to follow, the gather's hemicubes render beside
    // the rays (their time is then in "direct light and refinement" and "shooting" as well).
    rad::MeshingOptions options;
    options.gatherAhead = solve;
    const rad::MeshedScene meshed = rad::meshScene(std::move(scene), settings, options);
    const double meshing = rad::StageTimes::since(start);
    row.elements = meshed.mesh.elementCount();
    row.vertices = meshed.mesh.mesh.n_vertices();
    row.print("loading and splitting", loading, loadingPeak);
    for (const rad::StageTime& s : meshed.mesh.stats.stages.list()) row.print(s.name, s.seconds, s.peakMiB);
    row.print("direct light and refinement", meshing - meshed.mesh.stats.stages.total());
    const rad::GatherEstimate& gather = meshed.gather.estimate;
    std::fprintf(stderr, "bench_scale: gather %s: %.3g drawn triangles, %.3g located pixels, %.3g factors (%s)\n",
                 meshed.gather.on ? "on" : "skipped", gather.drawn, gather.located, gather.factors,
                 gather.iterates(rad::GatherOptions{}) ? "iterated" : "over its memory: gathered once");
    if (!solve) return 0;
    start = Clock::now();
    rad::RadiositySolve solving(meshed);
    while (solving.step()) {
    }
    row.print("shooting", rad::StageTimes::since(start));
    const rad::ProgressiveSolver& shot = solving.solver();
    std::fprintf(stderr, "bench_scale: %ld shots (%ld by clusters), %ld hemicubes, unshot %.3g\n", shot.shots(),
                 shot.clusterShots(), shot.hemicubes(), shot.unshotFraction());
    start = Clock::now();
    const rad::Solution solution = solving.bake();
    row.print(solution.gathered ? "final gather" : "baking", rad::StageTimes::since(start));
    std::fprintf(stderr, "bench_scale: gather hemicubes %.1f s (from the mesh on), its iteration %.1f s\n",
                 solution.gather.hemicubeSeconds, solution.gather.solveSeconds);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_scale: %s\n", e.what());
    return 1;
  }
  return 0;
}
