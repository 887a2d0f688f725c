// Benchmarks of the raster core: item+depth drawing of random small triangles, and a
// hemicube-like workload (5 faces of one view point, most triangles outside each face).
#include "display/raster/raster.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

namespace {

/// Three draws of `u`, z first (one per statement: a call's arguments are evaluated in an
/// unspecified order, and a benchmark's scene must be the same whatever the compiler).
glm::vec3 randomVec3(std::uniform_real_distribution<float>& u, std::mt19937& rng) {
  const float z = u(rng), y = u(rng), x = u(rng);
  return {x, y, z};
}

// `count` small random triangles (edges ~size) inside the box [-1, 1]^3.
void randomScene(size_t count, float size, uint32_t seed, std::vector<glm::vec3>& pos,
                 std::vector<uint32_t>& idx) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  pos.clear();
  idx.clear();
  for (size_t t = 0; t < count; ++t) {
    const glm::vec3 c = randomVec3(u, rng);
    for (int k = 0; k < 3; ++k) {
      idx.push_back(uint32_t(pos.size()));
      pos.push_back(c + size * randomVec3(u, rng));
    }
  }
}

glm::mat4 boxCamera() {
  return glm::perspective(glm::radians(60.0f), 1.0f, 0.1f, 10.0f) *
         glm::lookAt(glm::vec3(0.3f, 0.4f, 3.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
}

// Triangles per second of a benchmark drawing n triangles per iteration.
benchmark::Counter triangleRate(size_t n) {
  return benchmark::Counter(double(n), benchmark::Counter::kIsIterationInvariantRate);
}

// Item+depth drawing (clear + draw) of random triangles into 256x256, with the vertex transform
// timed or done once beforehand.
void itemDepth(benchmark::State& st, bool timeTransform) {
  const size_t n = size_t(st.range(0));
  std::vector<glm::vec3> pos;
  std::vector<uint32_t> idx;
  randomScene(n, 0.04f, 1, pos, idx);
  const glm::mat4 mvp = boxCamera();
  std::vector<glm::vec4> clip;
  raster::transform(mvp, pos, clip);
  raster::Target target(256, 256);
  const raster::State state;
  for (auto _ : st) {
    target.clearDepth();
    target.clearItem();
    if (timeTransform) raster::transform(mvp, pos, clip);
    raster::drawTriangles(target, state, clip.data(), clip.size(), idx.data(), n);
    benchmark::DoNotOptimize(target.item.data());
  }
  st.counters["tri/s"] = triangleRate(n);
}

// Item+depth drawing of pre-transformed random small triangles.
void BM_ItemDepth(benchmark::State& st) { itemDepth(st, false); }
BENCHMARK(BM_ItemDepth)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);

// Same including the vertex transform.
void BM_TransformItemDepth(benchmark::State& st) { itemDepth(st, true); }
BENCHMARK(BM_TransformItemDepth)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);

// Smooth-shaded colour + depth (the generic path), for comparison.
void BM_SmoothColor(benchmark::State& st) {
  const size_t n = size_t(st.range(0));
  std::vector<glm::vec3> pos;
  std::vector<uint32_t> idx;
  randomScene(n, 0.04f, 1, pos, idx);
  std::vector<glm::vec4> clip, colors(pos.size());
  raster::transform(boxCamera(), pos, clip);
  for (size_t i = 0; i < pos.size(); ++i) colors[i] = glm::vec4(pos[i] * 0.5f + 0.5f, 1.0f);
  raster::Target target(256, 256, false, true);
  raster::State state;
  state.shade = raster::Shade::Smooth;
  for (auto _ : st) {
    target.clear();
    raster::drawTriangles(target, state, clip.data(), clip.size(), idx.data(), n, nullptr,
                          colors.data());
    benchmark::DoNotOptimize(target.color.data());
  }
  st.counters["tri/s"] = triangleRate(n);
}
BENCHMARK(BM_SmoothColor)->Arg(10000)->Unit(benchmark::kMicrosecond);

// Hemicube-like: a closed room of 10 000 shared-vertex triangles (a grid on each wall) plus
// clutter, seen from the middle of the floor: one 256x256 face up and four 256x128 half faces.
// Vertices are transformed once per face by a full matrix (a real hemicube permutes instead).
struct Room {
  std::vector<glm::vec3> pos;
  std::vector<uint32_t> idx;
};

Room makeRoom(size_t targetTriangles) {
  Room r;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // 6 walls of a 4 x 3 x 5 box, each an n x n grid of quads (2 triangles each).
  const int n = int(std::sqrt(double(targetTriangles) * 0.8 / 12.0));
  const glm::vec3 lo(-2, 0, -2.5f), hi(2, 3, 2.5f);
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      const uint32_t base = uint32_t(r.pos.size());
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          glm::vec3 p;
          p[axis] = side ? hi[axis] : lo[axis];
          p[a1] = lo[a1] + (hi[a1] - lo[a1]) * float(i) / float(n);
          p[a2] = lo[a2] + (hi[a2] - lo[a2]) * float(j) / float(n);
          r.pos.push_back(p);
        }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const uint32_t a = base + uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 2),
                         d = a + uint32_t(n + 1);
          r.idx.insert(r.idx.end(), {a, b, c, a, c, d});
        }
    }
  }
  // Clutter: small random triangles filling the rest of the budget.
  while (r.idx.size() / 3 < targetTriangles) {
    const glm::vec3 c = lo + (hi - lo) * randomVec3(u, rng);
    for (int k = 0; k < 3; ++k) {
      r.idx.push_back(uint32_t(r.pos.size()));
      r.pos.push_back(c + 0.15f * (randomVec3(u, rng) - 0.5f));
    }
  }
  return r;
}

void BM_HemicubeLike(benchmark::State& st) {
  const size_t n = size_t(st.range(0));
  const bool withTransform = st.range(1) != 0;
  const Room room = makeRoom(n);
  const glm::vec3 eye(0.1f, 0.001f, 0.2f);
  const float nearZ = 0.01f, farZ = 20.0f;
  // Up face: full 90 degree frustum; side faces: the upper half of a 90 degree frustum.
  const glm::mat4 full = glm::frustum(-nearZ, nearZ, -nearZ, nearZ, nearZ, farZ);
  const glm::mat4 half = glm::frustum(-nearZ, nearZ, 0.0f, nearZ, nearZ, farZ);
  const glm::vec3 dirs[4] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
  glm::mat4 mvp[5];
  mvp[0] = full * glm::lookAt(eye, eye + glm::vec3(0, 1, 0), glm::vec3(0, 0, -1));
  for (int k = 0; k < 4; ++k) mvp[k + 1] = half * glm::lookAt(eye, eye + dirs[k], glm::vec3(0, 1, 0));
  raster::Target top(256, 256);
  raster::Target side[4] = {raster::Target(256, 128), raster::Target(256, 128),
                            raster::Target(256, 128), raster::Target(256, 128)};
  raster::Target* faces[5] = {&top, &side[0], &side[1], &side[2], &side[3]};
  std::vector<glm::vec4> clip[5];
  for (int k = 0; k < 5; ++k) raster::transform(mvp[k], room.pos, clip[k]);
  const raster::State state;
  const size_t tris = room.idx.size() / 3;
  for (auto _ : st) {
    for (int k = 0; k < 5; ++k) {
      if (withTransform) raster::transform(mvp[k], room.pos, clip[k]);
      faces[k]->clearDepth();
      faces[k]->clearItem();
      raster::drawTriangles(*faces[k], state, clip[k].data(), clip[k].size(), room.idx.data(), tris);
    }
    benchmark::DoNotOptimize(top.item.data());
  }
  size_t covered = 0;
  for (auto* f : faces)
    for (uint32_t i : f->item) covered += i != raster::kNoItem;
  st.counters["covered"] = double(covered);
  st.counters["tri/s"] = triangleRate(tris);
}
BENCHMARK(BM_HemicubeLike)
    ->Args({10000, 0})
    ->Args({10000, 1})
    ->ArgNames({"tris", "xform"})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
