// One hemicube evaluation on the Cornell box, at about 10 000 and 100 000 triangles and
// R = 128, 256, 512: our raster core, and the identical item buffers through OSMesa.
// One iteration is one hemicube, so "Time" is the time per hemicube; wall-clock time is
// measured because llvmpipe draws on worker threads (its default: one per core).
//   build/bin/bench_hemicube [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "mesh/patch_mesh.h"
#include "mesh/scene.h"
#include "radiosity/hemicube.h"
#include "tests/bench/osmesa_item_buffer.h"

namespace {

struct Cornell {
  rad::Scene scene;
  rad::PatchMesh mesh;
  rad::HemicubeGeometry geometry;
};

/// The Cornell box meshed with this element edge (mm); cached across benchmarks.
const Cornell& cornell(double elementEdge) {
  static std::map<double, std::unique_ptr<Cornell>> cache;
  auto& c = cache[elementEdge];
  if (!c) {
    c = std::make_unique<Cornell>();
    c->scene = rad::loadScene(std::string(RAD_SOURCE_DIR) + "/scenes/cornell.json");
    c->mesh = rad::buildPatchMesh(c->scene, {elementEdge, 3 * elementEdge});
    c->geometry = rad::HemicubeGeometry::fromMesh(c->mesh);
  }
  return *c;
}

// Element edges giving about 10 000 and 100 000 triangles.
constexpr double kEdge10k = 33.5, kEdge100k = 10.0;

/// Shooting points: element centroids spread over the scene, cycled through.
struct Points {
  explicit Points(const rad::PatchMesh& m) : mesh(m) {}
  int next() { return index = (index + 7919) % mesh.elementCount(); }
  const rad::PatchMesh& mesh;
  int index = 0;
};

void setCounters(benchmark::State& state, const Cornell& c) {
  double tris = double(c.mesh.elementCount());
  state.counters["triangles"] = tris;
  state.counters["triangles_per_s"] =
      benchmark::Counter(tris, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_HemicubeCore(benchmark::State& state) {
  const Cornell& c = cornell(state.range(1) == 10 ? kEdge10k : kEdge100k);
  rad::Hemicube hemicube(c.geometry, int(state.range(0)), c.scene.diagonal());
  rad::FormFactors ff;
  Points points(c.mesh);
  for (auto _ : state) {
    int e = points.next();
    hemicube.compute(c.mesh.centroid(e), c.mesh.normal(e), rad::hemicubeRotation(1, e, 0), ff, {e});
    benchmark::DoNotOptimize(ff.sky);
  }
  setCounters(state, c);
}

void BM_HemicubeOsMesa(benchmark::State& state) {
  const Cornell& c = cornell(state.range(1) == 10 ? kEdge10k : kEdge100k);
  const int R = int(state.range(0));
  rad::Hemicube hemicube(c.geometry, R, c.scene.diagonal());
  static std::unique_ptr<bench::OsMesaItemBuffer> gl;
  if (!gl) gl = std::make_unique<bench::OsMesaItemBuffer>(1024, 1024);
  state.SetLabel(gl->renderer());
  std::vector<glm::vec4> clip;
  std::vector<uint32_t> items;
  Points points(c.mesh);
  for (auto _ : state) {
    int e = points.next();
    hemicube.prepare(c.mesh.centroid(e), c.mesh.normal(e), rad::hemicubeRotation(1, e, 0), {e});
    for (int f = 0; f < 5; ++f) {
      hemicube.faceClip(f, clip);
      gl->draw(R, f == 0 ? R : R / 2, clip.data(), clip.size(), hemicube.drawIndices().data(),
               hemicube.drawIds().size(), hemicube.drawIds().data(), items);
      benchmark::DoNotOptimize(items.data());
    }
  }
  setCounters(state, c);
}

// Arguments: resolution R, then 10 or 100 (thousand triangles).
BENCHMARK(BM_HemicubeCore)
    ->ArgsProduct({{128, 256, 512}, {10, 100}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_HemicubeOsMesa)
    ->ArgsProduct({{128, 256, 512}, {10, 100}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
