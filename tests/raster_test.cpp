// Tests of the raster core (display/raster/raster.h).
#include "display/raster/raster.h"
#include "tests/support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <ostream>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

namespace {

using raster::Cull;
using raster::kNoItem;
using raster::Shade;
using raster::State;
using raster::Target;

constexpr double kDepthTol = 1e-5;   // analytic vs rasterised depth
constexpr double kColorTol = 1e-5;   // analytic vs rasterised colour
constexpr double kEdgeMargin = 1.0;  // pixels this close to an analytic boundary are not judged

// A mesh in clip space, with optional per-triangle ids and per-vertex colours.
struct Mesh {
  std::vector<glm::vec4> clip;
  std::vector<uint32_t> idx;
  std::vector<uint32_t> ids;
  std::vector<glm::vec4> colors;
  size_t triangles() const { return idx.size() / 3; }
};

Target makeTarget(int w, int h, bool hits, bool color = false) {
  Target t(w, h, true, color);
  if (hits) t.hits.assign(size_t(w) * h, 0u);
  return t;
}

void draw(Target& t, const State& s, const Mesh& m) {
  raster::drawTriangles(t, s, m.clip.data(), m.clip.size(), m.idx.data(), m.triangles(),
                        m.ids.empty() ? nullptr : m.ids.data(),
                        m.colors.empty() ? nullptr : m.colors.data());
}

// Clip-space vertex at window position (x, y) of a w x h target, NDC depth z, scaled by cw.
glm::vec4 windowToClip(double x, double y, double z, int w, int h, float cw = 1.0f) {
  const float nx = float(x / w * 2.0 - 1.0), ny = float(y / h * 2.0 - 1.0);
  return glm::vec4(nx * cw, ny * cw, float(z) * cw, cw);
}

State countingState() {
  State s;
  s.depthTest = false;  // count every fragment, whatever its depth
  return s;
}

// Draws m with reversed depth (depth cleared to 0, test GREATER) and the given clip-space depth
// convention into a new w x h target with an item buffer.
Target drawReversed(const Mesh& m, int w, int h,
                    raster::ClipDepth clipDepth = raster::ClipDepth::NegativeOneToOne) {
  Target t = makeTarget(w, h, false);
  t.clearDepth(0.0f);
  State s;
  s.depthFunc = raster::DepthFunc::Greater;
  s.clipDepth = clipDepth;
  draw(t, s, m);
  return t;
}

// ---------------------------------------------------------------------------------------------

TEST(Raster, HitsHookCountsOverdraw) {
  // The coverage tests rely on the hits hook: make sure overlapping draws are counted twice.
  Target t = makeTarget(16, 16, true);
  Mesh m;
  m.clip = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {-1, 1, 0, 1}};
  m.idx = {0, 1, 2, 0, 1, 2};
  draw(t, countingState(), m);
  EXPECT_EQ(t.hits[t.index(1, 1)], 2u);
  EXPECT_EQ(t.hits[t.index(15, 15)], 0u);
}

TEST(Raster, RowZeroIsBottom) {
  Target t = makeTarget(8, 8, false);
  Mesh m;  // a quad covering y_ndc in [-1, 0]: the lower half of the image
  m.clip = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 0, 0, 1}, {-1, 0, 0, 1}};
  m.idx = {0, 1, 2, 0, 2, 3};
  m.ids = {7, 7};
  draw(t, State{}, m);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) EXPECT_EQ(t.item[t.index(x, y)], y < 4 ? 7u : kNoItem) << x << "," << y;
}

// A jittered 37x23 vertex grid tiling the viewport, random diagonals and random w: every pixel
// is hit exactly once, by a triangle that really contains its centre.
TEST(Raster, GridCoversEveryPixelExactlyOnce) {
  constexpr int W = 160, H = 96, NX = 37, NY = 23;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3), wdist(0.3, 4.0);
  std::uniform_int_distribution<int> coin(0, 1), pick(0, 3);
  std::vector<glm::dvec2> pos(NX * NY);
  Mesh m;
  for (int j = 0; j < NY; ++j) {
    for (int i = 0; i < NX; ++i) {
      double x = double(i) / (NX - 1) * W, y = double(j) / (NY - 1) * H;
      if (i > 0 && i < NX - 1) x += jitter(rng) * W / (NX - 1);
      if (j > 0 && j < NY - 1) y += jitter(rng) * H / (NY - 1);
      // Put many interior vertices exactly on pixel centres, pixel edges or pixel corners.
      const int mode = pick(rng);
      const bool ix = i > 0 && i < NX - 1, iy = j > 0 && j < NY - 1;
      if (ix && mode < 3) x = mode == 0 ? std::floor(x) + 0.5 : std::round(x);
      if (iy && mode < 3) y = mode == 2 ? std::round(y) : std::floor(y) + 0.5;
      pos[j * NX + i] = {x, y};
      m.clip.push_back(windowToClip(x, y, 0.0, W, H, float(wdist(rng))));
    }
  }
  for (int j = 0; j + 1 < NY; ++j) {
    for (int i = 0; i + 1 < NX; ++i) {
      const uint32_t a = j * NX + i, b = a + 1, c = a + NX + 1, d = a + NX;
      if (coin(rng)) m.idx.insert(m.idx.end(), {a, b, c, a, c, d});
      else m.idx.insert(m.idx.end(), {a, b, d, b, c, d});
    }
  }
  // The jittered mesh must be a valid tiling (all counter-clockwise as built); then reverse
  // the winding of random triangles, which must not matter without culling.
  for (size_t t = 0; t < m.triangles(); ++t) {
    const glm::dvec2 a = pos[m.idx[3 * t]], b = pos[m.idx[3 * t + 1]], c = pos[m.idx[3 * t + 2]];
    ASSERT_GE((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y), 0.0) << "test mesh folds";
    if (coin(rng)) std::swap(m.idx[3 * t + 1], m.idx[3 * t + 2]);
  }
  Target t = makeTarget(W, H, true);
  draw(t, countingState(), m);
  int bad = 0;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const uint32_t h = t.hits[t.index(x, y)];
      if (h != 1 && ++bad < 10) ADD_FAILURE() << "pixel " << x << "," << y << " hit " << h << " times";
      // The winner contains the pixel centre (up to the snapping tolerance).
      const uint32_t tri = t.item[t.index(x, y)];
      ASSERT_LT(tri, m.triangles());
      const glm::dvec2 p(x + 0.5, y + 0.5);
      for (int k = 0; k < 3; ++k) {
        const glm::dvec2 a = pos[m.idx[3 * tri + k]], b = pos[m.idx[3 * tri + (k + 1) % 3]];
        const glm::dvec2 c = pos[m.idx[3 * tri + (k + 2) % 3]];
        const auto side = [&](glm::dvec2 q) { return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x); };
        const double dist = side(p) / glm::length(b - a) * (side(c) > 0 ? 1 : -1);
        EXPECT_GT(dist, -0.01) << "pixel " << x << "," << y << " not inside triangle " << tri;
      }
    }
  }
  EXPECT_EQ(bad, 0);
}

// Pixel centres exactly on shared edges go to the triangle below a horizontal edge and to the
// right of a vertical one (top-left rule in the y-up window).
TEST(Raster, FillRuleIsTopLeft) {
  constexpr int W = 8, H = 8;
  // Four quads meeting at (3.5, 4.5): the split lines run through pixel centres.
  const double xs[3] = {0, 3.5, 8}, ys[3] = {0, 4.5, 8};
  Mesh m;
  for (int qy = 0; qy < 2; ++qy)
    for (int qx = 0; qx < 2; ++qx) {
      const uint32_t b = uint32_t(m.clip.size());
      m.clip.push_back(windowToClip(xs[qx], ys[qy], 0, W, H));
      m.clip.push_back(windowToClip(xs[qx + 1], ys[qy], 0, W, H));
      m.clip.push_back(windowToClip(xs[qx + 1], ys[qy + 1], 0, W, H));
      m.clip.push_back(windowToClip(xs[qx], ys[qy + 1], 0, W, H));
      m.idx.insert(m.idx.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
      const uint32_t quad = uint32_t(qy * 2 + qx);
      m.ids.insert(m.ids.end(), {quad, quad});
    }
  Target t = makeTarget(W, H, true);
  draw(t, countingState(), m);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const uint32_t want = uint32_t((y <= 4 ? 0 : 2) + (x >= 3 ? 1 : 0));
      ASSERT_EQ(t.hits[t.index(x, y)], 1u) << x << "," << y;
      ASSERT_EQ(t.item[t.index(x, y)], want) << x << "," << y;
    }
}

// A closed fan around a shared vertex placed on a pixel centre, pixel edge or corner, with
// spokes through many pixel centres; outer vertices far outside the viewport.
struct FanCase {
  const char* name;
  double x, y;
};
void PrintTo(const FanCase& c, std::ostream* os) { *os << c.name; }

class FanTest : public ::testing::TestWithParam<FanCase> {};

TEST_P(FanTest, CoversEveryPixelExactlyOnce) {
  constexpr int W = 64, H = 64;
  const glm::dvec2 centre(GetParam().x, GetParam().y);
  const int dirs[16][2] = {{1, 0},  {2, 1},   {1, 1},   {1, 2},   {0, 1},  {-1, 2}, {-1, 1}, {-2, 1},
                           {-1, 0}, {-2, -1}, {-1, -1}, {-1, -2}, {0, -1}, {1, -2}, {1, -1}, {2, -1}};
  for (float cw : {1.0f, 2.0f}) {
    Mesh m;
    m.clip.push_back(windowToClip(centre.x, centre.y, 0.0, W, H, cw));
    for (const auto& d : dirs)
      m.clip.push_back(windowToClip(centre.x + 100.0 * d[0], centre.y + 100.0 * d[1], 0.0, W, H, cw));
    for (uint32_t k = 0; k < 16; ++k) {
      const uint32_t a = 1 + k, b = 1 + (k + 1) % 16;
      if (k % 3 == 0) m.idx.insert(m.idx.end(), {0, b, a});  // mixed windings
      else m.idx.insert(m.idx.end(), {0, a, b});
    }
    Target t = makeTarget(W, H, true);
    draw(t, countingState(), m);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        ASSERT_EQ(t.hits[t.index(x, y)], 1u) << "pixel " << x << "," << y << " w=" << cw;
  }
}

INSTANTIATE_TEST_SUITE_P(Raster, FanTest,
                         ::testing::Values(FanCase{"PixelCentre", 32.5, 32.5},
                                           FanCase{"VerticalPixelEdge", 32.0, 32.5},
                                           FanCase{"HorizontalPixelEdge", 32.5, 32.0},
                                           FanCase{"PixelCorner", 32.0, 32.0},
                                           FanCase{"Anywhere", 31.3, 33.7},
                                           FanCase{"CornerPixelCentre", 0.5, 63.5}),
                         [](const ::testing::TestParamInfo<FanCase>& i) { return std::string(i.param.name); });

TEST(Raster, DepthOrderIndependentOfSubmissionOrder) {
  constexpr int W = 64, H = 64;
  // Three overlapping triangles at NDC depths 0.5, -0.2, 0.1 (id 1 nearest-but-one, ...).
  const std::array<std::array<glm::dvec2, 3>, 3> tri = {{{{{4, 4}, {60, 8}, {20, 60}}},
                                                        {{{10, 50}, {14, 2}, {62, 40}}},
                                                        {{{2, 20}, {50, 10}, {40, 62}}}}};
  const double depth[3] = {0.5, -0.2, 0.1};
  std::array<int, 3> order = {0, 1, 2};
  std::vector<uint32_t> reference;
  int perms = 0;
  do {
    Mesh m;
    for (int k : order) {
      for (const auto& p : tri[k]) m.clip.push_back(windowToClip(p.x, p.y, depth[k], W, H, 1.5f));
      const uint32_t b = uint32_t(m.clip.size() - 3);
      m.idx.insert(m.idx.end(), {b, b + 1, b + 2});
      m.ids.push_back(uint32_t(k));
    }
    Target t = makeTarget(W, H, false);
    draw(t, State{}, m);
    // Where all three overlap, the nearest (id 1) wins; check analytically at a pixel deep inside.
    EXPECT_EQ(t.item[t.index(30, 30)], 1u);
    EXPECT_NEAR(t.depth[t.index(30, 30)], (depth[1] + 1) / 2, kDepthTol);
    if (reference.empty()) reference = t.item;
    EXPECT_EQ(t.item, reference) << "permutation " << perms;
    ++perms;
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(perms, 6);
  // Analytic check of the reference: every pixel whose centre is inside some triangle (with a
  // margin) shows the nearest of them.
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const glm::dvec2 p(x + 0.5, y + 0.5);
      int best = -1;
      bool ambiguous = false;
      for (int k = 0; k < 3; ++k) {
        double minDist = 1e9;
        for (int e = 0; e < 3; ++e) {
          const glm::dvec2 a = tri[k][e], b = tri[k][(e + 1) % 3], c = tri[k][(e + 2) % 3];
          const auto side = [&](glm::dvec2 q) { return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x); };
          minDist = std::min(minDist, side(p) / glm::length(b - a) * (side(c) > 0 ? 1 : -1));
        }
        if (std::fabs(minDist) < kEdgeMargin) ambiguous = true;
        if (minDist > 0 && (best < 0 || depth[k] < depth[best])) best = k;
      }
      if (ambiguous) continue;
      EXPECT_EQ(reference[size_t(y) * W + x], best < 0 ? kNoItem : uint32_t(best)) << x << "," << y;
    }
  }
}

// Perspective camera used by the 3D tests: eye at height `eyeY`, looking down -z, pitched.
struct Camera {
  int W, H;
  double fovy, nearZ, farZ, eyeY, pitch;
  glm::dmat4 view() const {
    return glm::rotate(glm::dmat4(1.0), -pitch, glm::dvec3(1, 0, 0)) *
           glm::translate(glm::dmat4(1.0), glm::dvec3(0, -eyeY, 0));
  }
  glm::dmat4 proj() const { return glm::perspective(fovy, double(W) / H, nearZ, farZ); }
  glm::dmat4 mvp() const { return proj() * view(); }
  // World-space ray through the centre of pixel (x, y) (window coordinates, y up).
  void ray(double x, double y, glm::dvec3& origin, glm::dvec3& dir) const {
    const glm::dmat4 inv = glm::inverse(mvp());
    glm::dvec4 a = inv * glm::dvec4(x / W * 2 - 1, y / H * 2 - 1, -1, 1);
    glm::dvec4 b = inv * glm::dvec4(x / W * 2 - 1, y / H * 2 - 1, 1, 1);
    origin = glm::dvec3(a) / a.w;
    dir = glm::normalize(glm::dvec3(b) / b.w - origin);
  }
  double windowDepth(const glm::dvec3& p) const {
    const glm::dvec4 c = mvp() * glm::dvec4(p, 1.0);
    return (c.z / c.w + 1) / 2;
  }
  double eyeDepth(const glm::dvec3& p) const { return -(view() * glm::dvec4(p, 1.0)).z; }
};

Mesh worldMesh(const Camera& cam, const std::vector<glm::dvec3>& pts, std::vector<uint32_t> idx) {
  Mesh m;
  std::vector<glm::vec3> p;
  for (const auto& q : pts) p.push_back(glm::vec3(q));
  raster::transform(glm::mat4(cam.mvp()), p, m.clip);
  m.idx = std::move(idx);
  return m;
}

// Hit of a pixel-centre ray with the ground y = 0 inside a convex xz polygon, within near/far.
// Returns 1 inside, 0 outside, -1 if a neighbour (+-kEdgeMargin px) disagrees (not judged).
int groundClass(const Camera& cam, double x, double y, const std::vector<glm::dvec3>& poly,
                glm::dvec3* hit = nullptr) {
  auto inside = [&](double px, double py, glm::dvec3* out) {
    glm::dvec3 o, d;
    cam.ray(px, py, o, d);
    if (d.y >= 0) return false;
    const glm::dvec3 p = o + d * (-o.y / d.y);
    if (out) *out = p;
    const double ez = cam.eyeDepth(p);
    if (ez < cam.nearZ || ez > cam.farZ) return false;
    for (size_t k = 0; k < poly.size(); ++k) {
      const glm::dvec3 a = poly[k], b = poly[(k + 1) % poly.size()];
      if ((b.x - a.x) * (p.z - a.z) - (b.z - a.z) * (p.x - a.x) > 0) return false;  // CW in xz
    }
    return true;
  };
  const bool c = inside(x, y, hit);
  for (double dx : {-kEdgeMargin, kEdgeMargin})
    if (inside(x + dx, y, nullptr) != c || inside(x, y + dx, nullptr) != c) return -1;
  return c ? 1 : 0;
}

// A big ground triangle reaching behind the camera: cut by the near plane (and maybe the guard
// band), not dropped. Covered pixels and depths match the analytic ground plane.
TEST(Raster, NearPlaneClippedGroundTriangle) {
  const Camera cam{96, 64, glm::radians(60.0), 0.1, 200.0, 1.0, 0.0};
  // Counter-clockwise seen from above (+y), i.e. clockwise in xz with our test convention.
  const std::vector<glm::dvec3> tri = {{-30, 0, 5}, {30, 0, 5}, {0, 0, -60}};
  Mesh m = worldMesh(cam, tri, {0, 1, 2});
  ASSERT_LT(m.clip[0].w, 0.0f);  // really behind the eye
  Target t = makeTarget(cam.W, cam.H, true);
  State s;
  draw(t, s, m);
  int covered = 0, judged = 0;
  for (int y = 0; y < cam.H; ++y) {
    for (int x = 0; x < cam.W; ++x) {
      glm::dvec3 p(0.0);
      const int cls = groundClass(cam, x + 0.5, y + 0.5, tri, &p);
      if (cls < 0) continue;
      ++judged;
      const size_t i = t.index(x, y);
      EXPECT_EQ(t.item[i] == 0u, cls == 1) << "pixel " << x << "," << y;
      if (cls == 1 && t.item[i] == 0u) {
        ++covered;
        EXPECT_NEAR(t.depth[i], cam.windowDepth(p), kDepthTol) << "pixel " << x << "," << y;
      }
    }
  }
  EXPECT_GT(covered, cam.W * cam.H / 4);
  EXPECT_GT(judged, cam.W * cam.H * 3 / 4);
}

// A jittered ground grid seen from very low: the near plane cuts many adjacent triangles inside
// the image. Every pixel is hit at most once, and exactly once where the ground is visible.
TEST(Raster, NearClippedGridIsWatertight) {
  const Camera cam{128, 96, glm::radians(70.0), 0.1, 100.0, 0.05, glm::radians(-15.0)};
  constexpr int N = 41;
  const double x0 = -6, x1 = 6, z0 = 1, z1 = -12;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::uniform_int_distribution<int> coin(0, 1);
  std::vector<glm::dvec3> pts;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      const double dx = (x1 - x0) / (N - 1), dz = (z1 - z0) / (N - 1);
      double x = x0 + i * dx, z = z0 + j * dz;
      if (i > 0 && i < N - 1) x += jitter(rng) * dx;
      if (j > 0 && j < N - 1) z += jitter(rng) * dz;
      pts.push_back({x, 0, z});
    }
  std::vector<uint32_t> idx;
  for (int j = 0; j + 1 < N; ++j)
    for (int i = 0; i + 1 < N; ++i) {
      const uint32_t a = j * N + i, b = a + 1, c = a + N + 1, d = a + N;
      if (coin(rng)) idx.insert(idx.end(), {a, b, c, a, c, d});
      else idx.insert(idx.end(), {a, b, d, b, c, d});
    }
  Mesh m = worldMesh(cam, pts, idx);
  Target t = makeTarget(cam.W, cam.H, true);
  draw(t, countingState(), m);
  const std::vector<glm::dvec3> outline = {{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}};
  int clippedRows = 0, seen = 0;
  for (int y = 0; y < cam.H; ++y) {
    bool rowHasNearCut = false;
    for (int x = 0; x < cam.W; ++x) {
      const uint32_t h = t.hits[t.index(x, y)];
      ASSERT_LE(h, 1u) << "double hit at " << x << "," << y;
      glm::dvec3 p(0.0);
      const int cls = groundClass(cam, x + 0.5, y + 0.5, outline, &p);
      if (cls < 0) continue;
      ASSERT_EQ(h, uint32_t(cls)) << "pixel " << x << "," << y;
      seen += cls;
      // A ground point (inside the outline) closer than the near plane: the cut is in view.
      glm::dvec3 o, d;
      cam.ray(x + 0.5, y + 0.5, o, d);
      if (d.y < 0 && cam.eyeDepth(o + d * (-o.y / d.y)) < cam.nearZ) rowHasNearCut = true;
    }
    clippedRows += rowHasNearCut;
  }
  EXPECT_GT(clippedRows, 5) << "the near plane cut should be visible";
  EXPECT_GT(seen, cam.W * cam.H / 3);
}

// Perspective-correct barycentrics of pixel (x, y) on a world triangle, from ray/plane hit.
bool worldBarycentric(const Camera& cam, double x, double y, const std::array<glm::dvec3, 3>& v,
                      glm::dvec3& bary) {
  glm::dvec3 o, d;
  cam.ray(x, y, o, d);
  const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
  const double t = glm::dot(v[0] - o, n) / glm::dot(d, n);
  const glm::dvec3 p = o + t * d;
  const double a = glm::dot(n, n);
  const double b2 = glm::dot(n, glm::cross(v[1] - v[0], p - v[0])) / a;  // weight of v2
  const double b1 = glm::dot(n, glm::cross(p - v[0], v[2] - v[0])) / a;  // weight of v1
  bary = glm::dvec3(1 - b1 - b2, b1, b2);
  return cam.eyeDepth(p) >= cam.nearZ && bary.x > 1e-3 && bary.y > 1e-3 && bary.z > 1e-3;
}

TEST(Raster, GouraudIsPerspectiveCorrect) {
  const Camera cam{80, 60, glm::radians(60.0), 0.1, 100.0, 0.0, 0.0};
  const std::array<glm::vec4, 3> col = {glm::vec4(1, 0, 0, 1), glm::vec4(0, 1, 0, 0.5f),
                                        glm::vec4(0, 0.2f, 1, 0)};
  // One triangle well in front, one reaching behind the eye (clipped, attributes interpolated).
  const std::array<std::array<glm::dvec3, 3>, 2> tris = {
      {{{{-1, -1, -2}, {3, -0.5, -9}, {-0.5, 1.5, -3}}}, {{{-2, -1, 1}, {2, -0.8, -1}, {0, 2, -8}}}}};
  for (const auto& v : tris) {
    Mesh m = worldMesh(cam, {v[0], v[1], v[2]}, {0, 1, 2});
    m.colors.assign(col.begin(), col.end());
    Target t = makeTarget(cam.W, cam.H, false, true);
    State s;
    s.shade = Shade::Smooth;
    draw(t, s, m);
    int checked = 0;
    for (int y = 0; y < cam.H; ++y)
      for (int x = 0; x < cam.W; ++x) {
        glm::dvec3 b;
        if (!worldBarycentric(cam, x + 0.5, y + 0.5, v, b)) continue;
        const size_t i = t.index(x, y);
        ASSERT_EQ(t.item[i], 0u) << x << "," << y;
        const glm::dvec4 want = b.x * glm::dvec4(col[0]) + b.y * glm::dvec4(col[1]) + b.z * glm::dvec4(col[2]);
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(t.color[i][k], want[k], kColorTol) << x << "," << y;
        ++checked;
      }
    EXPECT_GT(checked, 200);
  }
}

TEST(Raster, FlatShadingUsesLastVertex) {
  constexpr int W = 32, H = 32;
  const glm::vec4 c0(1, 0, 0, 1), c1(0, 1, 0, 1), c2(0, 0, 1, 1);
  Mesh m;
  m.clip = {windowToClip(2, 2, 0, W, H), windowToClip(30, 4, 0, W, H), windowToClip(10, 30, 0, W, H),
            // a clipped one (vertex 4 behind the eye: w < 0)
            glm::vec4(0.2f, -0.9f, 0.8f, 1.0f), glm::vec4(0.5f, 0.5f, -1.2f, -1.0f),
            glm::vec4(0.9f, 0.9f, 0.8f, 1.0f)};
  m.colors = {c0, c1, c2, c0, c1, c2};
  State s;
  s.shade = Shade::Flat;
  s.depthTest = false;
  for (const auto& order : std::vector<std::array<uint32_t, 3>>{{0, 1, 2}, {1, 0, 2}, {2, 0, 1}, {3, 4, 5}, {5, 3, 4}}) {
    m.idx.assign(order.begin(), order.end());
    Target t = makeTarget(W, H, false, true);
    draw(t, s, m);
    int n = 0;
    for (size_t i = 0; i < t.item.size(); ++i) {
      if (t.item[i] == kNoItem) continue;
      ++n;
      ASSERT_EQ(t.color[i], m.colors[order[2]]);
    }
    EXPECT_GT(n, 20);
  }
}

TEST(Raster, CullingRemovesClockwiseOnly) {
  constexpr int W = 32, H = 16;
  Mesh m;
  m.clip = {windowToClip(1, 1, 0, W, H), windowToClip(15, 1, 0, W, H), windowToClip(8, 15, 0, W, H),
            windowToClip(17, 1, 0, W, H), windowToClip(31, 1, 0, W, H), windowToClip(24, 15, 0, W, H),
            // near-clipped, clockwise
            glm::vec4(0.2f, 0.9f, 0.8f, 1.0f), glm::vec4(0.5f, -0.5f, -1.2f, -1.0f), glm::vec4(0.9f, -0.9f, 0.8f, 1.0f)};
  m.idx = {0, 1, 2, /* CW: */ 3, 5, 4, 6, 7, 8};
  m.ids = {10, 20, 30};
  for (Cull cull : {Cull::None, Cull::Back}) {
    Target t = makeTarget(W, H, false);
    State s;
    s.cull = cull;
    s.depthTest = false;
    draw(t, s, m);
    auto count = [&](uint32_t id) { return std::count(t.item.begin(), t.item.end(), id); };
    EXPECT_GT(count(10), 40);
    if (cull == Cull::Back) {
      EXPECT_EQ(count(20), 0);
      EXPECT_EQ(count(30), 0);
    } else {
      EXPECT_GT(count(20), 40);
      EXPECT_GT(count(30), 20);
    }
  }
}

TEST(Raster, DegenerateTrianglesDrawNothing) {
  Target t = makeTarget(16, 16, true);
  Mesh m;
  m.clip = {{-1, -1, 0, 1}, {1, 1, 0, 1}, {0, 0, 0, 1}, {0.5f, -0.5f, 0, 1}};
  m.idx = {0, 1, 2, 3, 3, 1, 0, 0, 0};
  draw(t, countingState(), m);
  for (uint32_t h : t.hits) ASSERT_EQ(h, 0u);
}

TEST(Raster, DepthIsFloat32) {
  static_assert(std::is_same_v<decltype(Target::depth)::value_type, float>);
  // Depths 0.25 and 0.25 + 2^-25 (one float ulp): beyond any 24-bit fixed-point buffer.
  const float zA = -0.5f, zB = -0.5f + std::ldexp(1.0f, -24);
  for (int order = 0; order < 2; ++order) {
    Mesh m;
    for (float z : order ? std::array<float, 2>{zA, zB} : std::array<float, 2>{zB, zA}) {
      const uint32_t b = uint32_t(m.clip.size());
      m.clip.insert(m.clip.end(), {{-1, -1, z, 1}, {1, -1, z, 1}, {-1, 1, z, 1}});
      m.idx.insert(m.idx.end(), {b, b + 1, b + 2});
      m.ids.push_back(z == zA ? 1u : 2u);
    }
    Target t = makeTarget(8, 8, false);
    draw(t, State{}, m);
    EXPECT_EQ(t.item[t.index(1, 1)], 1u);
    EXPECT_EQ(t.depth[t.index(1, 1)], 0.25f);
  }
}

TEST(Raster, NearAndFarRejectAndClip) {
  constexpr int W = 32, H = 32;
  Mesh m;
  m.clip = {{-1, -1, 1.5f, 1}, {1, -1, 1.2f, 1}, {0, 1, 3.0f, 1},       // beyond far
            {-1, -1, -1.5f, 1}, {1, -1, -1.2f, 1}, {0, 1, -3.0f, 1},    // in front of near
            {-1, -1, -1.2f, -1}, {1, -1, -2.2f, -2}, {0, 1, -1.2f, -1}};  // behind the eye
  m.idx = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  Target t = makeTarget(W, H, true);
  draw(t, countingState(), m);
  for (uint32_t h : t.hits) ASSERT_EQ(h, 0u);

  // A quad whose NDC depth goes from 0 (left) to 2 (right): only x_ndc <= 0 survives the far cut.
  Mesh q;
  q.clip = {{-1, -1, 0, 1}, {1, -1, 2, 1}, {1, 1, 2, 1}, {-1, 1, 0, 1}};
  q.idx = {0, 1, 2, 0, 2, 3};
  Target u = makeTarget(W, H, true);
  draw(u, countingState(), q);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) ASSERT_EQ(u.hits[u.index(x, y)], x < W / 2 ? 1u : 0u) << x << "," << y;
  // depth written: depth test on
  Target v = makeTarget(W, H, false);
  draw(v, State{}, q);
  for (int x = 0; x < W / 2; ++x)
    EXPECT_NEAR(v.depth[v.index(x, 5)], 0.5 + 0.5 * (x + 0.5) / (W / 2), kDepthTol);
}

TEST(Raster, GuardBandHugeTrianglesTileExactly) {
  constexpr int W = 48, H = 40;
  Mesh m;  // a quad far beyond the guard band, with different w, cut along a diagonal
  m.clip = {{-3e6f, -2e6f, 0, 1}, {5e5f, -7e5f, 0, 0.25f}, {4e6f, 5e6f, 0, 2}, {-1e6f, 2e6f, 0, 0.5f}};
  m.idx = {0, 1, 2, 0, 2, 3};
  Target t = makeTarget(W, H, true);
  draw(t, countingState(), m);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) ASSERT_EQ(t.hits[t.index(x, y)], 1u) << x << "," << y;
}

TEST(Raster, ScissorLimitsDrawing) {
  Target t = makeTarget(16, 16, true);
  Mesh m;
  m.clip = {{-1, -1, 0, 1}, {3, -1, 0, 1}, {-1, 3, 0, 1}};
  m.idx = {0, 1, 2};
  State s = countingState();
  s.scissorTest = true;
  s.scissor = raster::Rect{3, 5, 4, 6};
  draw(t, s, m);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      ASSERT_EQ(t.hits[t.index(x, y)], (x >= 3 && x < 7 && y >= 5 && y < 11) ? 1u : 0u);
}

// The fast item+depth path and the generic path share one rasteriser: identical results.
TEST(Raster, FastPathMatchesGenericPath) {
  constexpr int W = 100, H = 70;
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> u(-1.6f, 1.6f), uw(-0.3f, 2.0f);
  Mesh m;
  for (int k = 0; k < 3000; ++k) {
    const float w = uw(rng);
    m.clip.push_back({u(rng) * std::fabs(w), u(rng) * std::fabs(w), u(rng) * std::fabs(w), w});
  }
  std::uniform_int_distribution<uint32_t> vi(0, 2999);
  for (int k = 0; k < 2000; ++k) m.idx.insert(m.idx.end(), {vi(rng), vi(rng), vi(rng)});
  for (auto func : {raster::DepthFunc::Less, raster::DepthFunc::Greater}) {
    State s;
    s.depthFunc = func;
    const float clearTo = func == raster::DepthFunc::Less ? 1.0f : 0.0f;
    Target fast = makeTarget(W, H, false);
    Target generic = makeTarget(W, H, true);  // the hits hook forces the generic path
    fast.clearDepth(clearTo);
    generic.clearDepth(clearTo);
    draw(fast, s, m);
    draw(generic, s, m);
    EXPECT_EQ(fast.item, generic.item);
    EXPECT_EQ(fast.depth, generic.depth);
    EXPECT_GT(std::count_if(fast.item.begin(), fast.item.end(), [](uint32_t i) { return i != kNoItem; }),
              W * H / 2);
  }
}

// A grid mesh tiling a w x h window, cells of about `spacing` pixels (triangles from sub-pixel
// to a few hundred pixels), random diagonals and windings. If `snapped`, the grid lines are
// multiples of spacing (a multiple of 0.5: many edges through pixel centres) and w is a power
// of 2 per vertex, so that window positions are exact; otherwise vertices are jittered and w
// random; times wScale (a power of 2). NDC depth z, or z = near in clip space (reversed [0, 1]
// depth: depth = near/w) if near > 0. Item ids count from firstId.
void addGrid(Mesh& m, std::mt19937& rng, int w, int h, double spacing, bool snapped, double z,
             float near, float wScale, uint32_t firstId) {
  const int nx = int(std::ceil(w / spacing)) + 1, ny = int(std::ceil(h / spacing)) + 1;
  std::uniform_real_distribution<double> jitter(-0.3, 0.3), wdist(0.5, 3.0);
  std::uniform_int_distribution<int> coin(0, 1), pow2(-1, 2);
  const uint32_t base = uint32_t(m.clip.size());
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      double x = std::min(i * spacing, double(w)), y = std::min(j * spacing, double(h));
      if (!snapped && i > 0 && i < nx - 1) x += jitter(rng) * spacing;
      if (!snapped && j > 0 && j < ny - 1) y += jitter(rng) * spacing;
      const float cw = wScale * (snapped ? std::ldexp(1.0f, pow2(rng)) : float(wdist(rng)));
      glm::vec4 v = windowToClip(x, y, z, w, h, cw);
      if (near > 0) v.z = near;
      m.clip.push_back(v);
    }
  }
  uint32_t id = firstId;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const uint32_t a = base + j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      uint32_t t[2][3] = {{a, b, c}, {a, c, d}};
      if (coin(rng)) t[0][2] = d, t[1][0] = b;  // the other diagonal: (a, b, d), (b, c, d)
      for (auto& tri : t) {
        if (coin(rng)) std::swap(tri[1], tri[2]);
        m.idx.insert(m.idx.end(), {tri[0], tri[1], tri[2]});
        m.ids.push_back(id++);
      }
    }
}

// One configuration of FastPathMatchesGenericPathOnFineMeshes.
struct FineMeshCase {
  int w, h;
  double spacing;
  bool snapped, reversed, cull, scissor;
};

// The draw state of a case: reversed [0, 1] depth, back-face culling and a scissor rectangle as
// the case asks.
State fineMeshState(const FineMeshCase& k) {
  State s;
  if (k.reversed) {
    s.depthFunc = raster::DepthFunc::Greater;
    s.clipDepth = raster::ClipDepth::ZeroToOne;
  }
  if (k.cull) s.cull = Cull::Back;
  if (k.scissor) {
    s.scissorTest = true;
    s.scissor = {7, 5, k.w - 20, k.h - 9};
  }
  return s;
}

// One mesh of `first` then `second` (ids kept).
Mesh concatenated(const Mesh& first, const Mesh& second) {
  Mesh both = first;
  const uint32_t shift = uint32_t(both.clip.size());
  both.clip.insert(both.clip.end(), second.clip.begin(), second.clip.end());
  for (uint32_t i : second.idx) both.idx.push_back(i + shift);
  both.ids.insert(both.ids.end(), second.ids.begin(), second.ids.end());
  return both;
}

// A new w x h target with an item buffer (and the hits hook if asked), depth cleared to
// clearTo, with m drawn into it.
Target drawnTarget(int w, int h, bool hits, float clearTo, const State& s, const Mesh& m) {
  Target t = makeTarget(w, h, hits);
  t.clearDepth(clearTo);
  draw(t, s, m);
  return t;
}

// A single layer drawn without culling: every pixel inside the scissor rectangle (if on) is hit
// exactly once by the generic path (hits hook) and gets an item from the fast path; no other.
void expectCoveredOnce(const Target& fast, const Target& generic, const State& s) {
  for (int y = 0; y < fast.height; ++y)
    for (int x = 0; x < fast.width; ++x) {
      const bool inside = !s.scissorTest || (x >= s.scissor.x && x < s.scissor.x + s.scissor.width &&
                                             y >= s.scissor.y && y < s.scissor.y + s.scissor.height);
      ASSERT_EQ(generic.hits[generic.index(x, y)], inside ? 1u : 0u) << x << "," << y;
      ASSERT_EQ(fast.item[fast.index(x, y)] != kNoItem, inside) << x << "," << y;
    }
}

// The fast path's setups for small triangles (whole-box coverage with 16-bit coordinates, and
// rows of chunks) against the generic path on fine meshes: identical items and depths, and a
// single layer covers every pixel exactly once. Two overlapping layers, both depth
// conventions, culling, scissor, and target widths that are not multiples of 4 (or below 4).
TEST(Raster, FastPathMatchesGenericPathOnFineMeshes) {
  const FineMeshCase cases[] = {
      {101, 67, 0.5, true, true, false, false},   {101, 67, 0.7, false, true, false, false},
      {101, 67, 1.5, true, true, false, false},   {101, 67, 2.3, false, true, false, false},
      {96, 64, 1.0, true, false, false, false},   {96, 64, 1.3, false, false, false, false},
      {96, 64, 9.5, true, true, false, false},    {53, 70, 30.0, false, false, false, false},
      {53, 70, 70.0, false, true, false, false},  {101, 67, 1.7, false, true, true, false},
      {101, 67, 1.5, true, true, false, true},    {101, 67, 1.1, false, false, false, true},
      {101, 67, 7.0, true, true, false, true},    {101, 67, 13.3, false, true, false, true},
      {3, 9, 0.5, true, true, false, false},      {6, 5, 0.6, false, false, false, false},
      {256, 128, 1.9, false, true, false, false}, {256, 128, 2.0, true, true, false, false}};
  std::mt19937 rng(2024);
  for (const FineMeshCase& k : cases) {
    SCOPED_TRACE(::testing::Message() << k.w << "x" << k.h << " spacing " << k.spacing
                                      << (k.snapped ? " snapped" : "") << (k.reversed ? " reversed" : "")
                                      << (k.cull ? " cull" : "") << (k.scissor ? " scissor" : ""));
    const float near = k.reversed ? 1e-3f : 0.0f;
    Mesh layer0, layer1;
    // Layer 1 is nearer in both conventions: smaller NDC z, and smaller w (larger near/w).
    addGrid(layer0, rng, k.w, k.h, k.spacing, k.snapped, 0.1, near, 16.0f, 0);
    addGrid(layer1, rng, k.w, k.h, k.spacing * 1.5, k.snapped, -0.2, near, 1.0f,
            uint32_t(layer0.triangles()));
    Mesh both = concatenated(layer1, layer0);
    const State s = fineMeshState(k);
    const float clearTo = k.reversed ? 0.0f : 1.0f;
    for (const Mesh* m : {&layer0, &both}) {
      const Target fast = drawnTarget(k.w, k.h, false, clearTo, s, *m);
      // The hits hook forces the generic path.
      const Target generic = drawnTarget(k.w, k.h, true, clearTo, s, *m);
      ASSERT_EQ(fast.item, generic.item);
      ASSERT_EQ(fast.depth, generic.depth);
      if (m == &layer0 && !k.cull) {
        expectCoveredOnce(fast, generic, s);
        if (HasFatalFailure()) return;
      }
    }
    // The nearer layer wins wherever it covers a pixel, whatever the order of submission.
    const Target ab = drawnTarget(k.w, k.h, false, clearTo, s, both);
    Target ba = drawnTarget(k.w, k.h, false, clearTo, s, layer0);
    draw(ba, s, layer1);
    const Target near1 = drawnTarget(k.w, k.h, false, clearTo, s, layer1);
    ASSERT_EQ(ab.item, ba.item);
    ASSERT_EQ(ab.depth, ba.depth);
    for (size_t i = 0; i < ab.item.size(); ++i) {
      if (near1.item[i] != kNoItem) {
        ASSERT_EQ(ab.item[i], near1.item[i]) << "pixel " << i;
      }
    }
  }
}

// Reversed depth (clear to 0, test GREATER): the largest depth wins whatever the order.
TEST(Raster, DepthFuncGreater) {
  constexpr int W = 16, H = 16;
  const float z[3] = {0.5f, -0.2f, 0.1f};  // NDC depths of three full-screen triangles
  std::array<int, 3> order = {0, 1, 2};
  do {
    Mesh m;
    for (int k : order) {
      const uint32_t b = uint32_t(m.clip.size());
      m.clip.insert(m.clip.end(), {{-1, -1, z[k], 1}, {3, -1, z[k], 1}, {-1, 3, z[k], 1}});
      m.idx.insert(m.idx.end(), {b, b + 1, b + 2});
      m.ids.push_back(uint32_t(k));
    }
    const Target t = drawReversed(m, W, H);
    for (size_t i = 0; i < t.item.size(); ++i) {
      ASSERT_EQ(t.item[i], 0u);
      ASSERT_EQ(t.depth[i], 0.75f);
    }
  } while (std::next_permutation(order.begin(), order.end()));
}

TEST(Raster, NonIndexedDrawAndBadIndices) {
  Mesh m;  // a full-screen quad as two non-indexed triangles
  m.clip = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1}, {-1, -1, 0, 1}, {1, 1, 0, 1}, {-1, 1, 0, 1}};
  Target t = makeTarget(8, 8, true);
  raster::drawTriangles(t, countingState(), m.clip.data(), m.clip.size(), nullptr, 2);
  for (uint32_t h : t.hits) ASSERT_EQ(h, 1u);
  EXPECT_EQ(t.item[t.index(7, 0)], 0u);  // ids default to the triangle index
  EXPECT_EQ(t.item[t.index(0, 7)], 1u);
  const uint32_t bad[3] = {0, 1, 6};
  rad::test::expectError<std::out_of_range>([&] { raster::drawTriangles(t, State{}, m.clip.data(), m.clip.size(), bad, 1); },
                                       {"raster::drawTriangles", "vertex index out of range"});
  const uint32_t huge[9] = {0, 1, 2, 3, 0x80000001u, 5, 0, 1, 2};  // beyond int32 as well
  rad::test::expectError<std::out_of_range>([&] { raster::drawTriangles(t, State{}, m.clip.data(), m.clip.size(), huge, 3); },
                                       {"raster::drawTriangles", "vertex index out of range"});
}

TEST(Raster, TransformMatchesMatrixProduct) {
  const glm::mat4 mvp = glm::perspective(1.0f, 1.3f, 0.1f, 50.0f) *
                        glm::lookAt(glm::vec3(1, 2, 3), glm::vec3(0), glm::vec3(0, 1, 0));
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, -2, 3}, {-4, 5, 0.5f}};
  std::vector<glm::vec4> c;
  raster::transform(mvp, p, c);
  ASSERT_EQ(c.size(), p.size());
  for (size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(c[i][k], (mvp * glm::vec4(p[i], 1))[k], 1e-5);
}

TEST(Raster, ClearResetsBuffers) {
  Target t(4, 3, true, true);
  t.hits.assign(12, 5);
  t.depth[2] = 0.1f;
  t.item[3] = 4;
  t.color[5] = glm::vec4(1);
  t.clear();
  for (size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(t.depth[i], 1.0f);
    EXPECT_EQ(t.item[i], kNoItem);
    EXPECT_EQ(t.color[i], glm::vec4(0));
    EXPECT_EQ(t.hits[i], 0u);
  }
  rad::test::expectError<std::invalid_argument>([] { (void)Target(0, 5); }, {"raster::Target", "size must be within 1..kMaxSize"});
}

}  // namespace

// Reversed depth with the [0, 1] convention (glClipControl ZERO_TO_ONE), as the hemicube uses
// it: z = near, so depth = near/w keeps float's relative precision; nearer wins with GREATER
// in both submission orders, through the vectorised vertex stage (6 vertices) and the clipper.
TEST(Raster, ReversedZeroToOneDepthKeepsRelativePrecision) {
  constexpr int W = 8, H = 8;
  const float kNear = 1e-4f;
  const float dist[2] = {135.0f, 135.0f * (1 + 4e-6f)};  // 4e-6 apart: far beyond [-1,1] depth's reach
  for (int first = 0; first < 2; ++first) {
    Mesh m;
    for (int k : {first, 1 - first}) {
      const float w = dist[k];
      const uint32_t b = uint32_t(m.clip.size());
      m.clip.insert(m.clip.end(), {{-w, -w, kNear, w}, {3 * w, -w, kNear, w}, {-w, 3 * w, kNear, w}});
      m.idx.insert(m.idx.end(), {b, b + 1, b + 2});
      m.ids.push_back(uint32_t(k));
    }
    const Target t = drawReversed(m, W, H, raster::ClipDepth::ZeroToOne);
    for (size_t i = 0; i < t.item.size(); ++i) {
      ASSERT_EQ(t.item[i], 0u) << "order " << first;
      ASSERT_NEAR(t.depth[i] / (kNear / dist[0]), 1.0f, 1e-6f);
    }
  }
  // A triangle reaching behind the near plane (w < z) is cut there, not dropped: its visible
  // part covers the pixels in front.
  Mesh m;
  m.clip = {{-1, -1, kNear, 1}, {1, -1, kNear, 1}, {0, 1e-5f, kNear, 1e-5f}, {0, 0, kNear, 1}};
  m.idx = {0, 1, 2};
  m.ids = {7};
  const Target t = drawReversed(m, W, H, raster::ClipDepth::ZeroToOne);
  int covered = 0;
  for (auto id : t.item) covered += id == 7u;
  EXPECT_GT(covered, 0);
}

// Regression (a hemicube leak found in the closed-cube furnace): a triangle with one vertex
// just behind the eye is cut by the near plane at two points close together in clip space but
// far apart on screen. Clipping in float put those points in the wrong order in the guard band,
// the clipped polygon turned concave and a whole fan triangle was dropped (450 of 4096 pixels
// of a hemicube face saw the sky). Coverage must match an exact ray test of every pixel centre.
TEST(Raster, NearPlaneCutNearTheEyeStaysConvex) {
  const int W = 64, H = 64;
  const float kNear = 1.73205e-07f;
  std::vector<glm::vec4> clip = {{-0.0107927f, 0.00814682f, kNear, -1.73205e-06f},
                                 {0.085464f, -0.0310745f, kNear, 0.103939f},
                                 {-0.0107927f, 0.00814682f, kNear, 0.166665f}};
  Target t(W, H, true, false);
  t.clearDepth(0.0f);
  t.clearItem();
  State s;
  s.depthFunc = raster::DepthFunc::Greater;
  s.clipDepth = raster::ClipDepth::ZeroToOne;
  const uint32_t idx[3] = {0, 1, 2}, id = 7;
  raster::drawTriangles(t, s, clip.data(), 3, idx, 1, &id);
  // Exact: the ray (x, y, w) = λ·(ndc x, ndc y, 1) meets the triangle at w = λ >= near.
  auto det = [](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) { return glm::dot(a, glm::cross(b, c)); };
  glm::dvec3 a(clip[0].x, clip[0].y, clip[0].w), b(clip[1].x, clip[1].y, clip[1].w),
      c(clip[2].x, clip[2].y, clip[2].w);
  int expected = 0, mismatched = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      glm::dvec3 r((x + 0.5) / W * 2 - 1, (y + 0.5) / H * 2 - 1, 1);
      double e0 = det(b, c, r), e1 = det(c, a, r), e2 = det(a, b, r);
      bool same = (e0 > 0 && e1 > 0 && e2 > 0) || (e0 < 0 && e1 < 0 && e2 < 0);
      double lambda = det(a, b, c) / (e0 + e1 + e2);
      bool inside = same && lambda >= kNear;
      expected += inside;
      mismatched += inside != (t.item[t.index(x, y)] == id);
    }
  EXPECT_GT(expected, 400);
  EXPECT_LE(mismatched, 4) << "of " << expected << " pixels";
}

// ---- Lines (raster::drawLines) ----------------------------------------------------------------

namespace {

// Draws one segment between window points (x0, y0, z0) and (x1, y1, z1) (NDC depth z) with the
// hits hook on and no depth test; returns the hit counts.
std::vector<uint32_t> lineHits(int w, int h, glm::dvec3 a, glm::dvec3 b) {
  Target t = makeTarget(w, h, true);
  const glm::vec4 clip[2] = {windowToClip(a.x, a.y, a.z, w, h, 2.0f),
                             windowToClip(b.x, b.y, b.z, w, h, 0.5f)};
  raster::drawLines(t, countingState(), clip, 2, nullptr, 1, glm::vec4(1.0f));
  return t.hits;
}

TEST(RasterLines, OnePixelPerColumnOnPixelCentres) {
  constexpr int W = 16, H = 8;
  // x-major: columns whose centre lies in [1.2, 9.8) -> 1..9, row floor(3.7) = 3.
  std::vector<uint32_t> hits = lineHits(W, H, {1.2, 3.7, 0}, {9.8, 3.7, 0});
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      EXPECT_EQ(hits[size_t(y) * W + x], (y == 3 && x >= 1 && x <= 9) ? 1u : 0u) << x << "," << y;
  // A diagonal slope: one pixel per column, row = floor of the line's y at the column centre.
  hits = lineHits(W, H, {0.0, 0.0, 0}, {16.0, 8.0, 0});
  for (int x = 0; x < W; ++x) {
    const int y = int(std::floor((x + 0.5) * 0.5));
    int inColumn = 0;
    for (int j = 0; j < H; ++j) inColumn += int(hits[size_t(j) * W + x]);
    EXPECT_EQ(inColumn, 1) << x;
    EXPECT_EQ(hits[size_t(y) * W + x], 1u) << x;
  }
}

TEST(RasterLines, DirectionDoesNotMatter) {
  constexpr int W = 24, H = 24;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-4.0, 28.0);
  for (int i = 0; i < 200; ++i) {
    const double ay = u(rng), ax = u(rng), by = u(rng), bx = u(rng);  // one draw each, in a fixed order
    const glm::dvec3 a(ax, ay, 0.1), b(bx, by, -0.3);
    const std::vector<uint32_t> ab = lineHits(W, H, a, b), ba = lineHits(W, H, b, a);
    ASSERT_EQ(ab, ba) << i;
    // Steep lines: at most one pixel per row.
    if (std::abs(b.y - a.y) > std::abs(b.x - a.x))
      for (int y = 0; y < H; ++y) {
        int inRow = 0;
        for (int x = 0; x < W; ++x) inRow += int(ab[size_t(y) * W + x]);
        ASSERT_LE(inRow, 1) << i;
      }
  }
}

TEST(RasterLines, ViewportAndNearPlaneClipping) {
  constexpr int W = 10, H = 10;
  // Far beyond the viewport on both sides: exactly the W columns of row 5.
  std::vector<uint32_t> hits = lineHits(W, H, {-1000.0, 5.5, 0}, {1000.0, 5.5, 0});
  for (int x = 0; x < W; ++x) EXPECT_EQ(hits[size_t(5) * W + x], 1u);
  uint32_t total = 0;
  for (uint32_t h : hits) total += h;
  EXPECT_EQ(total, uint32_t(W));
  // Crossing the near plane (z = -w): only the part in front is drawn. With w = 1 and x going
  // -1 .. 1 while z goes -3 .. 1, the near plane is met at x = 0 (window x = 5).
  Target t = makeTarget(W, H, true);
  const glm::vec4 seg[2] = {{-1, 0.1f, -3, 1}, {1, 0.1f, 1, 1}};
  raster::drawLines(t, countingState(), seg, 2, nullptr, 1, glm::vec4(1.0f));
  for (int x = 0; x < W; ++x) EXPECT_EQ(t.hits[size_t(5) * W + x], x >= 5 ? 1u : 0u) << x;
  // Entirely behind the eye (w < 0) or in front of the near plane: nothing.
  t.clear();
  const glm::vec4 behind[2] = {{-1, 0, 2, -1}, {1, 0, 2, -1}};
  raster::drawLines(t, countingState(), behind, 2, nullptr, 1, glm::vec4(1.0f));
  for (uint32_t h : t.hits) EXPECT_EQ(h, 0u);
  // Bad indices.
  const uint32_t bad[2] = {0, 2};
  rad::test::expectError<std::out_of_range>([&] { raster::drawLines(t, countingState(), seg, 2, bad, 1, glm::vec4(1.0f)); },
                                       {"raster::drawLines", "vertex index out of range"});
}

TEST(RasterLines, DepthTestWithBiasTowardTheViewer) {
  constexpr int W = 16, H = 16;
  // A full-screen triangle at NDC depth 0 (window depth 0.5), a line on it and one behind it.
  Mesh m;
  m.clip = {{-1, -1, 0, 1}, {3, -1, 0, 1}, {-1, 3, 0, 1}};
  m.idx = {0, 1, 2};
  const glm::vec4 red(1, 0, 0, 1), green(0, 1, 0, 1);
  m.colors = {red, red, red};
  auto run = [&](float z, float bias, raster::DepthFunc func) {
    Target t(W, H, false, true);
    State s;
    s.shade = Shade::Flat;
    s.depthFunc = func;
    if (func == raster::DepthFunc::Greater) t.clearDepth(0.0f);
    raster::drawTriangles(t, s, m.clip.data(), 3, m.idx.data(), 1, nullptr, m.colors.data());
    const glm::vec4 seg[2] = {{-1, 0.05f, z, 1}, {1, 0.05f, z, 1}};
    raster::drawLines(t, s, seg, 2, nullptr, 1, green, bias);
    int shown = 0;
    for (int x = 0; x < W; ++x) shown += t.color[t.index(x, 8)] == green;
    return std::make_pair(shown, t.depth[t.index(3, 8)]);
  };
  using raster::DepthFunc;
  EXPECT_EQ(run(0.0f, 0.0f, DepthFunc::Less).first, 0);         // equal depth fails LESS
  auto biased = run(0.0f, 1e-4f, DepthFunc::Less);
  EXPECT_EQ(biased.first, W);                                    // the bias lifts it
  EXPECT_FLOAT_EQ(biased.second, 0.5f - 1e-4f);                  // and its depth is written
  EXPECT_EQ(run(0.01f, 1e-4f, DepthFunc::Less).first, 0);       // behind by more than the bias
  EXPECT_EQ(run(0.0f, 1e-4f, DepthFunc::Greater).first, W);     // reversed: bias is added
  EXPECT_EQ(run(-0.01f, 1e-4f, DepthFunc::Greater).first, 0);
}

}  // namespace
