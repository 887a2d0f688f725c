// One hemicube evaluation on the Cornell box, at about 10 000 and 100 000 triangles and
// R = 32 ... 512: our raster core, and the identical item buffers through OSMesa; then in a
// generated building of k × k rooms (about 12 000 triangles each), from the surfaces of its
// middle room, and in the interiors of ../shared/scenes/bitterli (their faces split into
// four up to twice), from element centroids. The last argument is the culling: 0 none
// (every element), 1 hidden (subtrees below the base plane or hidden), 2 auto (the
// default: 1 where it pays, else 0).
// One iteration is one hemicube, so "Time" is the time per hemicube; wall-clock time is
// measured because llvmpipe draws on worker threads (its default: one per core).
//   build/bin/bench_hemicube [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <tuple>

#include "mesh/patch_mesh.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/formfactors/hemicube.h"
#include "tests/bench/osmesa_item_buffer.h"
#include "tests/room_grid.h"

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
/// for the ratio table printed at the end: the core's with its culling as the backend.
std::map<std::tuple<std::string, int, int>, double> msPerHemicube;

/// The culling of benchmark argument `arg` and its name.
rad::HemicubeCulling culling(int64_t arg) {
  const rad::HemicubeCulling c[] = {rad::HemicubeCulling::None, rad::HemicubeCulling::Hidden,
                                    rad::HemicubeCulling::Auto};
  return c[arg];
}
const char* cullingName(int64_t arg) {
  const char* names[] = {"none", "hidden", "auto"};
  return names[arg];
}

/// Times the benchmark loop by the wall clock, as Google Benchmark's real time does.
class Stopwatch {
 public:
  explicit Stopwatch(benchmark::State& s) : state_(s), start_(std::chrono::steady_clock::now()) {}
  double record(const std::string& backend) {
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    return msPerHemicube[{backend, int(state_.range(0)), int(state_.range(1))}] = ms / double(state_.iterations());
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
  hemicube.setCulling(culling(state.range(2)));
  rad::FormFactors ff;
  Points points(c.mesh);
  Stopwatch watch(state);
  for (auto _ : state) {
    int e = points.next();
    hemicube.compute(c.mesh.centroid(e), c.mesh.normal(e), rad::hemicubeRotation(1, e, 0), ff, {e});
    benchmark::DoNotOptimize(ff.sky);
  }
  watch.record(std::string("core ") + cullingName(state.range(2)));
  setCounters(state, c);
}

void BM_HemicubeOsMesa(benchmark::State& state) {
  const Cornell& c = cornell(state.range(1) == 10 ? kEdge10k : kEdge100k);
  const int R = int(state.range(0));
  rad::Hemicube hemicube(c.geometry, R, c.scene.diagonal());
  hemicube.setCulling(rad::HemicubeCulling::None);  // prepare() draws nothing itself
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
      gl->draw(R, f == 0 ? R : R / 2, draw.clip.data(), draw.clip.size(),
               draw.indices.empty() ? nullptr : draw.indices.data(), draw.ids.size(), draw.ids.data(), items);
      benchmark::DoNotOptimize(items.data());
    }
  }
  watch.record("osmesa");
  setCounters(state, c);
}

/// The building's triangles' legs (m): about 12 000 triangles a room.
constexpr double kBuildingEdge = 0.1;

struct Building {
  rad::test::RoomGrid grid;
  rad::HemicubeGeometry geometry;
  std::vector<int> middle;  ///< the elements of the middle room's own surfaces
};

/// The building of k × k rooms; cached across benchmarks.
const Building& building(int k) {
  static std::map<int, std::unique_ptr<Building>> cache;
  auto& b = cache[k];
  if (!b) {
    b = std::make_unique<Building>();
    b->grid.roomsX = b->grid.roomsZ = k;
    b->grid.edge = kBuildingEdge;
    b->geometry = rad::test::roomGrid(b->grid);
    const glm::dvec3 centre = b->grid.centre(k / 2, k / 2, 0);
    const double inner = 0.5 * (b->grid.room - b->grid.wall);
    const auto& g = b->geometry;
    for (size_t e = 0; e < g.elementCount(); ++e) {
      const glm::dvec3 p = g.positions[g.indices[3 * e]];
      if (std::abs(p.x - centre.x) < inner && std::abs(p.z - centre.z) < inner) b->middle.push_back(int(e));
    }
    b->geometry.hierarchy();  // built here, not in the first timed hemicube
  }
  return *b;
}

/// The centroid of element e.
glm::dvec3 centroid(const rad::HemicubeGeometry& g, int e) {
  const uint32_t* c = g.indices.data() + 3 * size_t(e);
  return (g.positions[c[0]] + g.positions[c[1]] + g.positions[c[2]]) / 3.0;
}

/// Milliseconds per hemicube in the building, per (culling, R, rooms per side).
std::map<std::tuple<int, int, int>, double> buildingMs;
/// Triangles in the building and drawn per hemicube (summed over the faces), per rooms per side
/// and (culling, R, rooms per side).
std::map<int, double> buildingTriangles;
std::map<std::tuple<int, int, int>, double> buildingDrawn;

void BM_HemicubeBuilding(benchmark::State& state) {
  const int R = int(state.range(0)), k = int(state.range(1)), cull = int(state.range(2));
  const Building& b = building(k);
  const double size = b.grid.room * k * std::sqrt(2.0);
  rad::Hemicube hemicube(b.geometry, R, size);
  hemicube.setCulling(culling(cull));
  rad::FormFactors ff;
  size_t index = 0;
  double drawn = 0, hidden = 0, tested = 0;
  Stopwatch watch(state);
  for (auto _ : state) {
    index = (index + 7919) % b.middle.size();
    const int e = b.middle[index];
    hemicube.compute(centroid(b.geometry, e), b.geometry.normals[size_t(e)], rad::hemicubeRotation(1, uint64_t(e), 0), ff, {e});
    drawn += double(hemicube.counts().drawn), hidden += double(hemicube.counts().hidden);
    tested += double(hemicube.counts().tested);
    benchmark::DoNotOptimize(ff.sky);
  }
  buildingMs[{cull, R, k}] = watch.record("building");
  buildingTriangles[k] = double(b.geometry.elementCount());
  buildingDrawn[{cull, R, k}] = drawn / double(state.iterations());
  state.counters["triangles"] = double(b.geometry.elementCount());
  state.counters["drawn"] = benchmark::Counter(drawn, benchmark::Counter::kAvgIterations);
  state.counters["hidden"] = benchmark::Counter(hidden, benchmark::Counter::kAvgIterations);
  state.counters["tested"] = benchmark::Counter(tested, benchmark::Counter::kAvgIterations);
  state.SetLabel(cullingName(cull));
}

// Arguments: resolution R, then 10 or 100 (thousand triangles), then the culling.
BENCHMARK(BM_HemicubeCore)
    ->ArgsProduct({{32, 64, 128, 256, 512}, {10, 100}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_HemicubeOsMesa)
    ->ArgsProduct({{32, 64, 128, 256, 512}, {10, 100}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The interiors of ../shared/scenes/bitterli (CC BY 3.0), when at hand.
const char* const kInteriors[] = {"staircase2", "living-room", "staircase"};

/// Adds triangle (a, b, c) split `levels` times into four by its edge midpoints.
void addSplit(rad::HemicubeGeometry& g, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int levels) {
  if (levels == 0) {
    if (glm::length(glm::cross(b - a, c - a)) > 0) g.addTriangle(a, b, c);
    return;
  }
  const glm::dvec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  for (const auto& t : {std::array{a, ab, ca}, std::array{ab, b, bc}, std::array{ca, bc, c}, std::array{ab, bc, ca}})
    addSplit(g, t[0], t[1], t[2], levels - 1);
}

struct Interior {
  rad::Scene scene;
  rad::HemicubeGeometry geometry;
};

/// Interior `index`'s faces as fans of triangles, each split `levels` times (×4^levels
/// triangles), or null when the scene is not at hand; cached across benchmarks.
const Interior* interior(int index, int levels) {
  static std::map<std::pair<int, int>, std::unique_ptr<Interior>> cache;
  auto& in = cache[{index, levels}];
  const std::string path = std::string(RAD_SOURCE_DIR) + "/../shared/scenes/bitterli/" + kInteriors[index] + "/scene.json";
  if (!in && std::ifstream(path)) {
    in = std::make_unique<Interior>();
    in->scene = rad::loadScene(path);
    for (const rad::Surface& s : in->scene.surfaces)
      for (const rad::Polygon& p : s.polygons)
        for (size_t k = 1; k + 1 < p.outer.size(); ++k) addSplit(in->geometry, p.outer[0], p.outer[k], p.outer[k + 1], levels);
    in->geometry.hierarchy();
  }
  return in.get();
}

/// Milliseconds per hemicube in an interior, per (culling, R, interior, levels).
std::map<std::tuple<int, int, int, int>, double> interiorMs;
std::map<std::pair<int, int>, double> interiorTriangles;

void BM_HemicubeInterior(benchmark::State& state) {
  const int R = int(state.range(0)), index = int(state.range(1)), levels = int(state.range(2));
  const int cull = int(state.range(3));
  const Interior* in = interior(index, levels);
  if (!in) {
    state.SkipWithError("the scene is not at hand in ../shared/scenes/bitterli");
    return;
  }
  const rad::HemicubeGeometry& g = in->geometry;
  rad::Hemicube hemicube(g, R, in->scene.diagonal());
  hemicube.setCulling(culling(cull));
  rad::FormFactors ff;
  size_t e = 0;
  double drawn = 0;
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    e = (e + 7919) % g.elementCount();
    hemicube.compute(centroid(g, int(e)), g.normals[e], rad::hemicubeRotation(1, e, 0), ff, {int(e)});
    drawn += double(hemicube.counts().drawn);
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  interiorMs[{cull, R, index, levels}] = ms / double(state.iterations());
  interiorTriangles[{index, levels}] = double(g.elementCount());
  state.counters["triangles"] = double(g.elementCount());
  state.counters["drawn"] = benchmark::Counter(drawn, benchmark::Counter::kAvgIterations);
  state.SetLabel(std::string(kInteriors[index]) + " " + cullingName(cull) + (hemicube.culling() == rad::HemicubeCulling::Hidden ? " (hidden)" : " (none)"));
}

/// Arguments: resolution R, interior, splits of each triangle into four (Modern Hall, the
/// smallest, up to 456 000 triangles; the others up to 1 000 000), culling.
void interiorArguments(benchmark::internal::Benchmark* b) {
  for (int R : {32, 64})
    for (auto [index, levels] : {std::pair{0, 0}, {0, 1}, {0, 2}, {1, 0}, {1, 1}, {2, 0}, {2, 1}})
      for (int cull : {0, 1, 2}) b->Args({R, index, levels, cull});
}
BENCHMARK(BM_HemicubeInterior)->Apply(interiorArguments)->Unit(benchmark::kMillisecond)->UseRealTime();

// Arguments: resolution R, rooms per side, culling.
BENCHMARK(BM_HemicubeBuilding)
    ->ArgsProduct({{32, 64}, {3, 6, 9}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The ratio llvmpipe time / our time (drawing the same triangles, no culling) for every
/// case both backends ran.
void printRatios() {
  std::printf("\nhemicube: ms per hemicube, our core vs llvmpipe (OSMesa), Cornell box\n");
  std::printf("%6s %10s %10s %10s %8s\n", "R", "triangles", "core", "llvmpipe", "ratio");
  for (const auto& [key, core] : msPerHemicube) {
    auto [backend, R, k] = key;
    auto gl = msPerHemicube.find({"osmesa", R, k});
    if (backend != "core none" || gl == msPerHemicube.end()) continue;
    std::printf("%6d %9dk %10.3f %10.3f %7.1fx\n", R, k, core, gl->second, gl->second / core);
  }
}

/// The building's ms per hemicube with each culling, and the speed-up of the default (auto).
void printBuilding() {
  if (buildingMs.empty()) return;
  std::printf("\nhemicube in a building of k x k rooms, from the middle room's surfaces\n");
  std::printf("%4s %3s %10s %9s %9s %9s %8s %10s\n", "R", "k", "triangles", "ms none", "ms hidden", "ms auto",
              "speed-up", "drawn");
  auto ms = [](int cull, int R, int k) {
    auto at = buildingMs.find({cull, R, k});
    return at == buildingMs.end() ? NAN : at->second;
  };
  for (const auto& [key, autoMs] : buildingMs) {
    auto [cull, R, k] = key;
    if (cull != 2) continue;
    std::printf("%4d %3d %10.0f %9.3f %9.3f %9.3f %7.1fx %10.0f\n", R, k, buildingTriangles[k], ms(0, R, k),
                ms(1, R, k), autoMs, ms(0, R, k) / autoMs, buildingDrawn[key]);
  }
}

/// Each interior's ms per hemicube with each culling.
void printInteriors() {
  if (interiorMs.empty()) return;
  std::printf("\nhemicube in the interiors of ../shared/scenes/bitterli, from element centroids\n");
  std::printf("%4s %-12s %10s %9s %9s %9s %8s\n", "R", "interior", "triangles", "ms none", "ms hidden", "ms auto",
              "speed-up");
  auto ms = [](int cull, int R, int i, int l) {
    auto at = interiorMs.find({cull, R, i, l});
    return at == interiorMs.end() ? NAN : at->second;
  };
  for (const auto& [key, autoMs] : interiorMs) {
    auto [cull, R, i, l] = key;
    if (cull != 2) continue;
    std::printf("%4d %-12s %10.0f %9.3f %9.3f %9.3f %7.1fx\n", R, kInteriors[i], interiorTriangles[{i, l}],
                ms(0, R, i, l), ms(1, R, i, l), autoMs, ms(0, R, i, l) / autoMs);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  printRatios();
  printBuilding();
  printInteriors();
  benchmark::Shutdown();
  return 0;
}
