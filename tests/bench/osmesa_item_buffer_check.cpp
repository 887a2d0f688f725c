// Standalone check (not built by CMake): the OSMesa item buffer against the raster core on the
// same random clip-space scenes, hemicube-style (reversed depth, z = near, w = distance).
//   g++ -O2 -std=c++17 -I/work/main tests/bench/osmesa_item_buffer_check.cpp
//       tests/bench/osmesa_item_buffer.cpp display/raster.cpp
//       $(pkg-config --cflags --libs osmesa) -o /tmp/osm_check
// (one line). llvmpipe's thread count follows LP_NUM_THREADS (default: the CPU count; 0 =
// rasterise in the calling thread, the fair single-thread comparison).
// Prints the fraction of pixels whose ids agree (and how many disagreeing pixels are not next
// to an id boundary in either image), plus rough per-draw timings of both.
#include "display/raster.h"
#include "tests/bench/osmesa_item_buffer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

namespace {

constexpr float kNear = 0.01f;

// Local coordinates (a, b, c) -> clip space of hemicube face f (as radiosity/hemicube.cpp).
glm::vec4 faceClip(int f, const glm::vec3& p) {
  const float a = p.x, b = p.y, c = p.z;
  switch (f) {
    case 0: return {a, b, kNear, c};
    case 1: return {b, 2 * c - a, kNear, a};
    case 2: return {-b, 2 * c + a, kNear, -a};
    case 3: return {-a, 2 * c - b, kNear, b};
    default: return {a, 2 * c + b, kNear, -b};
  }
}

struct Scene {
  std::vector<glm::vec3> local;  // shared vertices
  std::vector<uint32_t> indices, ids;
};

// Random triangles around the eye: mostly small, some large ones, many crossing the near
// plane (w = near) of one face or another. Vertices are shared between neighbouring
// triangles (strips), so the OSMesa side really has to expand them.
Scene randomScene(size_t triangles, uint32_t seed, float scale = 1.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), u01(0.0f, 1.0f);
  Scene s;
  while (s.ids.size() < triangles) {
    const glm::vec3 centre(2.0f * u(rng), 2.0f * u(rng), 0.3f + 1.5f * u(rng));
    const float size = scale * (u01(rng) < 0.05f ? 1.5f : 0.02f + 0.3f * u01(rng));
    // A strip of up to 4 triangles sharing vertices.
    const uint32_t base = uint32_t(s.local.size());
    for (int k = 0; k < 6; ++k)
      s.local.push_back(centre + size * glm::vec3(u(rng), u(rng), u(rng)));
    for (int k = 0; k < 4 && s.ids.size() < triangles; ++k) {
      s.indices.insert(s.indices.end(), {base + k, base + k + 1, base + k + 2});
      s.ids.push_back(uint32_t(rng()) % 0xFFFFFFF0u);  // all four bytes used
    }
  }
  return s;
}

struct Compare {
  size_t pixels = 0, agree = 0, interiorDisagree = 0, coveredCore = 0, coveredGl = 0;
};

// True if pixel (x, y) has a 4-neighbour with another id.
bool onBoundary(const std::vector<uint32_t>& img, int w, int h, int x, int y) {
  const uint32_t v = img[size_t(y) * w + x];
  const int dx[] = {1, -1, 0, 0}, dy[] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const int nx = x + dx[k], ny = y + dy[k];
    if (nx >= 0 && ny >= 0 && nx < w && ny < h && img[size_t(ny) * w + nx] != v) return true;
  }
  return false;
}

void compare(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b, int w, int h,
             Compare& c) {
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      ++c.pixels;
      c.coveredCore += a[i] != raster::kNoItem;
      c.coveredGl += b[i] != raster::kNoItem;
      if (a[i] == b[i])
        ++c.agree;
      else if (!onBoundary(a, w, h, x, y) && !onBoundary(b, w, h, x, y))
        ++c.interiorDisagree;
    }
}

using Clock = std::chrono::steady_clock;

}  // namespace

int main() {
  try {
    bench::OsMesaItemBuffer gl(256, 256);
    std::printf("GL_RENDERER: %s\n", gl.renderer().c_str());

    raster::State state;
    state.depthFunc = raster::DepthFunc::Greater;
    state.clipDepth = raster::ClipDepth::ZeroToOne;
    raster::Target top(256, 256), side(256, 128);
    std::vector<uint32_t> items;
    std::vector<glm::vec4> clip;

    // Agreement: 2000 triangles, 5 faces (top 256x256, sides 256x128), several seeds.
    bool ok = true;
    for (int pass = 0; pass < 4; ++pass) {
      const size_t n = pass % 2 == 0 ? 2000 : 10000;
      const float scale = pass < 2 ? 1.0f : 0.1f;
      Compare total[2];
      for (uint32_t seed = 1; seed <= 4; ++seed) {
        const Scene s = randomScene(n, seed, scale);
        for (int f = 0; f < 5; ++f) {
          clip.resize(s.local.size());
          for (size_t i = 0; i < clip.size(); ++i) clip[i] = faceClip(f, s.local[i]);
          raster::Target& t = f == 0 ? top : side;
          t.clearDepth(0.0f);
          t.clearItem();
          raster::drawTriangles(t, state, clip.data(), clip.size(), s.indices.data(),
                                s.ids.size(), s.ids.data());
          gl.draw(t.width, t.height, clip.data(), clip.size(), s.indices.data(), s.ids.size(),
                  s.ids.data(), items);
          compare(t.item, items, t.width, t.height, total[f == 0 ? 0 : 1]);
        }
      }
      for (int k = 0; k < 2; ++k) {
        const Compare& c = total[k];
        const double frac = double(c.agree) / double(c.pixels);
        std::printf(
            "%5zu %s tri, %s: ids agree on %.4f %% of %zu px; disagreeing px off any id boundary: "
            "%zu; covered core %.1f %%, GL %.1f %%\n",
            n, scale == 1.0f ? "large" : "small", k == 0 ? "top 256x256 " : "side 256x128",
            100.0 * frac, c.pixels,
            c.interiorDisagree, 100.0 * double(c.coveredCore) / double(c.pixels),
            100.0 * double(c.coveredGl) / double(c.pixels));
        ok = ok && frac > 0.99;
      }
    }

    // Rough timing per draw (clear + draw + for GL the expansion, upload and readback).
    // "large": the agreement scene (heavy overdraw); "small": triangles 10x smaller, closer
    // to a finely meshed hemicube scene; n = 0 is the fixed cost (clear and readback).
    struct Case {
      size_t n;
      float scale;
    };
    for (const Case c : {Case{0, 1.0f}, Case{2000, 1.0f}, Case{2000, 0.1f}, Case{10000, 1.0f},
                         Case{10000, 0.1f}, Case{100000, 1.0f}, Case{100000, 0.1f}}) {
      const Scene s = randomScene(c.n, 7, c.scale);
      for (int f = 0; f < 2; ++f) {
        clip.resize(s.local.size());
        for (size_t i = 0; i < clip.size(); ++i) clip[i] = faceClip(f, s.local[i]);
        raster::Target& t = f == 0 ? top : side;
        const int reps = c.n >= 100000 ? 20 : 100;
        double best[2] = {1e30, 1e30}, sum[2] = {0, 0};
        for (int r = 0; r < reps + 3; ++r) {
          const auto t0 = Clock::now();
          t.clearDepth(0.0f);
          t.clearItem();
          raster::drawTriangles(t, state, clip.data(), clip.size(), s.indices.data(),
                                s.ids.size(), s.ids.data());
          const auto t1 = Clock::now();
          gl.draw(t.width, t.height, clip.data(), clip.size(), s.indices.data(), s.ids.size(),
                  s.ids.data(), items);
          const auto t2 = Clock::now();
          if (r < 3) continue;  // warm-up (llvmpipe compiles its shaders on first use)
          const double us[2] = {std::chrono::duration<double, std::micro>(t1 - t0).count(),
                                std::chrono::duration<double, std::micro>(t2 - t1).count()};
          for (int k = 0; k < 2; ++k) {
            sum[k] += us[k];
            best[k] = std::min(best[k], us[k]);
          }
        }
        std::printf("timing %6zu %s tri, %s: core %8.1f us (best %8.1f), OSMesa %8.1f us "
                    "(best %8.1f)\n",
                    c.n, c.scale == 1.0f ? "large" : "small",
                    f == 0 ? "top 256x256 " : "side 256x128", sum[0] / reps, best[0],
                    sum[1] / reps, best[1]);
      }
    }
    std::printf(ok ? "OK\n" : "FAIL: agreement below 99 %%\n");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
