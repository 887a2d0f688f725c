// One hemicube evaluation on the Cornell box, at about 10 000 and 100 000 triangles and
// R = 128, 256, 512: our raster core, and the identical item buffers through OSMesa.
// One iteration is one hemicube, so "Time" is the time per hemicube; wall-clock time is
// measured because llvmpipe draws on worker threads (its default: one per core).
//   build/bin/bench_hemicube [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <tuple>

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

/// Milliseconds per hemicube of the last run of each (backend, R, thousands of triangles),
/// for the ratio table printed at the end.
std::map<std::tuple<std::string, int, int>, double> msPerHemicube;

/// Times the benchmark loop by the wall clock, as Google Benchmark's real time does.
class Stopwatch {
 public:
  explicit Stopwatch(benchmark::State& s) : state_(s), start_(std::chrono::steady_clock::now()) {}
  void record(const std::string& backend) {
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    msPerHemicube[{backend, int(state_.range(0)), int(state_.range(1))}] = ms / double(state_.iterations());
  }

 private:
  benchmark::State& state_;
  std::chrono::steady_clock::time_point start_;
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
  Stopwatch watch(state);
  for (auto _ : state) {
    int e = points.next();
    hemicube.compute(c.mesh.centroid(e), c.mesh.normal(e), rad::hemicubeRotation(1, e, 0), ff, {e});
    benchmark::DoNotOptimize(ff.sky);
  }
  watch.record("core");
  setCounters(state, c);
}

void BM_HemicubeOsMesa(benchmark::State& state) {
  const Cornell& c = cornell(state.range(1) == 10 ? kEdge10k : kEdge100k);
  const int R = int(state.range(0));
  rad::Hemicube hemicube(c.geometry, R, c.scene.diagonal());
  static std::unique_ptr<bench::OsMesaItemBuffer> gl;
  if (!gl) gl = std::make_unique<bench::OsMesaItemBuffer>(1024, 1024);
  state.SetLabel(gl->renderer());
  std::vector<uint32_t> items;
  Points points(c.mesh);
  Stopwatch watch(state);
  for (auto _ : state) {
    int e = points.next();
    hemicube.prepare(c.mesh.centroid(e), c.mesh.normal(e), rad::hemicubeRotation(1, e, 0), {e});
    for (int f = 0; f < 5; ++f) {
      const rad::Hemicube::FaceDraw& draw = hemicube.faceDraw(f);
      gl->draw(R, f == 0 ? R : R / 2, draw.clip.data(), draw.clip.size(), draw.indices.data(),
               draw.ids.size(), draw.ids.data(), items);
      benchmark::DoNotOptimize(items.data());
    }
  }
  watch.record("osmesa");
  setCounters(state, c);
}

// Arguments: resolution R, then 10 or 100 (thousand triangles).
BENCHMARK(BM_HemicubeCore)
    ->ArgsProduct({{32, 64, 128, 256, 512}, {10, 100}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_HemicubeOsMesa)
    ->ArgsProduct({{32, 64, 128, 256, 512}, {10, 100}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The ratio llvmpipe time / our time for every case both backends ran.
void printRatios() {
  std::printf("\nhemicube: ms per hemicube, our core vs llvmpipe (OSMesa), Cornell box\n");
  std::printf("%6s %10s %10s %10s %8s\n", "R", "triangles", "core", "llvmpipe", "ratio");
  for (const auto& [key, core] : msPerHemicube) {
    auto [backend, R, k] = key;
    auto gl = msPerHemicube.find({"osmesa", R, k});
    if (backend != "core" || gl == msPerHemicube.end()) continue;
    std::printf("%6d %9dk %10.3f %10.3f %7.1fx\n", R, k, core, gl->second, gl->second / core);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  printRatios();
  benchmark::Shutdown();
  return 0;
}
