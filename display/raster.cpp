// The raster core. One pipeline (outcodes -> homogeneous clipping -> snapping -> edge-function
// rasterisation), instantiated for the item+depth fast path and for the generic path.
#include "display/raster.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#if defined(__SSE2__) && !defined(RASTER_NO_SIMD)
#include <emmintrin.h>
#define RASTER_SSE2 1
#else
#define RASTER_SSE2 0
#endif

namespace raster {
namespace {

constexpr int32_t kOne = 1 << kSubpixelBits;  // one pixel in fixed point
constexpr int32_t kHalf = kOne / 2;           // pixel centre offset
// Guard band: window coordinates are kept within +-kGuardPixels, so snapped coordinates fit in
// 24 bits, edge-function coefficients in 25 bits and edge values (2 products) in 50 bits.
constexpr float kGuardPixels = 32768.0f - 256.0f;
static_assert(kGuardPixels >= 1.5f * kMaxSize, "guard band must contain the viewport with margin");

// Outcode bits. Bits 0-3: outside the viewport's left/right/bottom/top planes (used for the
// trivial reject only). Bits 4-9: the clipping planes (near, far, guard band left/right/bottom/
// top), in the order clipped.
constexpr int kPlaneCount = 6;
constexpr int kFirstPlaneBit = 4;
constexpr uint32_t kClipBits = 0x3Fu << kFirstPlaneBit;
constexpr uint32_t kGenerated = 0xFFFFFFFFu;  // CVert::src of a vertex made by clipping
constexpr int kMaxPoly = 16;                  // convex triangle clipped by 6 planes: <= 9

// Per-draw constants of the NDC -> window mapping.
struct Frame {
  float halfW, halfH;  // window = (ndc + 1) * half
  float gx, gy;        // guard band half-extent in NDC units
  float nearW;         // near plane z >= -nearW*w: 1 for OpenGL's [-1, 1], 0 for [0, 1]
  float zScale, zBias; // depth = z_ndc * zScale + zBias
};

// A product kept apart from the sum it feeds. Where the build allows FMA contraction (say
// -march=native), the compiler could fuse a*b + c in one copy of a formula and not in another
// (scalar and SSE2 vertex stage, outcodes and clipper, the rasterisers' depths); with this, all
// copies keep computing the same operations, bit for bit. Without FMA instructions (as in the
// default x86-64 build) there is nothing to fuse, and it compiles to nothing.
#if defined(__GNUC__) && defined(__x86_64__) && (defined(__FMA__) || defined(__FMA4__))
template <class T>
inline T rounded(T v) {
  __asm__("" : "+x"(v));
  return v;
}
#else
template <class T>
inline T rounded(T v) {
  return v;
}
#endif

// Signed distance of v to clipping plane p (0 near, 1 far, 2-5 guard left/right/bottom/top);
// inside iff >= 0. The outcodes and the clipper both use it, so they always agree.
inline float planeDist(const glm::vec4& v, int p, const Frame& f) {
  switch (p) {
    case 0: return v.z + rounded(f.nearW * v.w);
    case 1: return v.w - v.z;
    case 2: return v.x + rounded(f.gx * v.w);
    case 3: return rounded(f.gx * v.w) - v.x;
    case 4: return v.y + rounded(f.gy * v.w);
    default: return rounded(f.gy * v.w) - v.y;
  }
}

// Outcode of a clip-space vertex; NaN coordinates set bits (they end up clipped away).
inline uint32_t outcode(const glm::vec4& v, const Frame& f) {
  uint32_t c = uint32_t(!(v.x + v.w >= 0.0f)) | uint32_t(!(v.w - v.x >= 0.0f)) << 1 |
               uint32_t(!(v.y + v.w >= 0.0f)) << 2 | uint32_t(!(v.w - v.y >= 0.0f)) << 3;
  // w <= 0 with z inside [-w, w] is only the zero vector: flag it so it is never projected.
  c |= uint32_t(!(planeDist(v, 0, f) >= 0.0f) || !(v.w > 0.0f)) << kFirstPlaneBit;
  for (int p = 1; p < kPlaneCount; ++p)
    c |= uint32_t(!(planeDist(v, p, f) >= 0.0f)) << (kFirstPlaneBit + p);
  return c;
}

// Clip space -> (x_w, y_w, depth, 1/w).
inline glm::vec4 project(const glm::vec4& v, const Frame& f) {
  const float q = 1.0f / v.w;
  return glm::vec4((rounded(v.x * q) + 1.0f) * f.halfW, (rounded(v.y * q) + 1.0f) * f.halfH,
                   rounded(v.z * q * f.zScale) + f.zBias, q);
}

// Window coordinate -> fixed point, rounded to nearest even like cvtps2dq in vertexStage
// (|x| <= kGuardPixels + small, so the result fits easily).
inline int32_t toFixed(float x) {
#if RASTER_SSE2
  return _mm_cvtss_si32(_mm_set_ss(x * float(kOne)));
#else
  return static_cast<int32_t>(std::lrint(x * float(kOne)));
#endif
}

// Vertex stage: outcode and window coordinates of every vertex (garbage window coordinates
// where clipping bits are set; they are never used). The SSE2 version does exactly the same
// IEEE operations as outcode() and project(), so both agree bit for bit with the clipper.
void vertexStage(const glm::vec4* clip, size_t n, const Frame& f, glm::vec4* win, glm::ivec2* fixed,
                 uint16_t* codes) {
  size_t v = 0;
#if RASTER_SSE2
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 gx = _mm_set1_ps(f.gx), gy = _mm_set1_ps(f.gy);
  const __m128 hw = _mm_set1_ps(f.halfW), hh = _mm_set1_ps(f.halfH);
  const __m128 fixedScale = _mm_set1_ps(float(kOne));
  // Bit k of the code where distance d is not >= 0 (NaN included).
  auto bit = [&](__m128 d, int k) {
    return _mm_and_si128(_mm_castps_si128(_mm_cmpnge_ps(d, zero)), _mm_set1_epi32(1 << k));
  };
  for (; v + 4 <= n; v += 4) {
    __m128 x = _mm_loadu_ps(&clip[v].x), y = _mm_loadu_ps(&clip[v + 1].x);
    __m128 z = _mm_loadu_ps(&clip[v + 2].x), w = _mm_loadu_ps(&clip[v + 3].x);
    _MM_TRANSPOSE4_PS(x, y, z, w);
    const __m128 gxw = rounded(_mm_mul_ps(gx, w)), gyw = rounded(_mm_mul_ps(gy, w));
    __m128i c = _mm_or_si128(bit(_mm_add_ps(x, w), 0), bit(_mm_sub_ps(w, x), 1));
    c = _mm_or_si128(c, _mm_or_si128(bit(_mm_add_ps(y, w), 2), bit(_mm_sub_ps(w, y), 3)));
    const __m128i nearOut = _mm_or_si128(_mm_castps_si128(_mm_cmpnge_ps(_mm_add_ps(z, rounded(_mm_mul_ps(_mm_set1_ps(f.nearW), w))), zero)),
                                         _mm_castps_si128(_mm_cmpngt_ps(w, zero)));
    c = _mm_or_si128(c, _mm_and_si128(nearOut, _mm_set1_epi32(1 << kFirstPlaneBit)));
    c = _mm_or_si128(c, bit(_mm_sub_ps(w, z), kFirstPlaneBit + 1));
    c = _mm_or_si128(c, bit(_mm_add_ps(x, gxw), kFirstPlaneBit + 2));
    c = _mm_or_si128(c, bit(_mm_sub_ps(gxw, x), kFirstPlaneBit + 3));
    c = _mm_or_si128(c, bit(_mm_add_ps(y, gyw), kFirstPlaneBit + 4));
    c = _mm_or_si128(c, bit(_mm_sub_ps(gyw, y), kFirstPlaneBit + 5));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(codes + v), _mm_packs_epi32(c, c));
    const __m128 q = _mm_div_ps(one, w);
    __m128 wx = _mm_mul_ps(_mm_add_ps(rounded(_mm_mul_ps(x, q)), one), hw);
    __m128 wy = _mm_mul_ps(_mm_add_ps(rounded(_mm_mul_ps(y, q)), one), hh);
    __m128 wz = _mm_add_ps(rounded(_mm_mul_ps(_mm_mul_ps(z, q), _mm_set1_ps(f.zScale))),
                           _mm_set1_ps(f.zBias));
    __m128 wq = q;
    const __m128i fx = _mm_cvtps_epi32(_mm_mul_ps(wx, fixedScale));
    const __m128i fy = _mm_cvtps_epi32(_mm_mul_ps(wy, fixedScale));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&fixed[v]), _mm_unpacklo_epi32(fx, fy));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&fixed[v + 2]), _mm_unpackhi_epi32(fx, fy));
    _MM_TRANSPOSE4_PS(wx, wy, wz, wq);
    _mm_storeu_ps(&win[v].x, wx);
    _mm_storeu_ps(&win[v + 1].x, wy);
    _mm_storeu_ps(&win[v + 2].x, wz);
    _mm_storeu_ps(&win[v + 3].x, wq);
  }
#endif
  for (; v < n; ++v) {
    codes[v] = uint16_t(outcode(clip[v], f));
    win[v] = project(clip[v], f);
    fixed[v] = (codes[v] & kClipBits) ? glm::ivec2(0) : glm::ivec2(toFixed(win[v].x), toFixed(win[v].y));
  }
}


// A vertex ready for triangle setup.
struct SVert {
  int32_t X, Y;            // snapped window position
  float x, y, z, q;        // exact window position, depth, 1/w
  const glm::vec4* color;  // per-vertex colour (smooth shading only)
};

inline SVert makeSVert(const glm::vec4& win, const glm::vec4* color) {
  return SVert{toFixed(win.x), toFixed(win.y), win.x, win.y, win.z, win.w, color};
}
inline SVert makeSVert(const glm::vec4& win, const glm::ivec2& fixed, const glm::vec4* color) {
  return SVert{fixed.x, fixed.y, win.x, win.y, win.z, win.w, color};
}

// Twice the signed area in fixed point (> 0: counter-clockwise in the y-up window).
inline int64_t area2(const SVert& a, const SVert& b, const SVert& c) {
  return (int64_t(b.X) - a.X) * (int64_t(c.Y) - a.Y) - (int64_t(c.X) - a.X) * (int64_t(b.Y) - a.Y);
}

// Per-draw output pointers and state, plus the current triangle's constants.
struct Ctx {
  float* depth;
  uint32_t* item;      // null: not written
  glm::vec4* color;    // null: not written
  uint32_t* hits;      // null: not counted
  int width;
  int x0, y0, x1, y1;  // inclusive pixel range (viewport & scissor)
  bool cullBack, depthTest, depthWrite;
  uint32_t id;         // current triangle's item id
  glm::vec4 flat;      // current triangle's flat colour
};

// Gradient of an attribute with values a0,a1,a2 at the vertices of a window-space triangle.
struct Plane {
  double x10, y10, x20, y20, inv;
  void gradient(double a0, double a1, double a2, double& gx, double& gy) const {
    const double a10 = a1 - a0, a20 = a2 - a0;
    gx = (rounded(a10 * y20) - rounded(a20 * y10)) * inv;
    gy = (rounded(a20 * x10) - rounded(a10 * x20)) * inv;
  }
};

// Attribute planes of counter-clockwise triangle (v0, v1, v2), twice its snapped area `area`:
// from the exact (unsnapped) positions, or the snapped ones if those degenerate.
inline Plane makePlane(const SVert& v0, const SVert& v1, const SVert& v2, int64_t area) {
  Plane pl{double(v1.x) - v0.x, double(v1.y) - v0.y, double(v2.x) - v0.x, double(v2.y) - v0.y, 0};
  double det = rounded(pl.x10 * pl.y20) - rounded(pl.x20 * pl.y10);
  if (!(det > 0.0)) {
    const double s = 1.0 / kOne;
    pl = Plane{(v1.X - v0.X) * s, (v1.Y - v0.Y) * s, (v2.X - v0.X) * s, (v2.Y - v0.Y) * s, 0};
    det = double(area) * s * s;
  }
  pl.inv = 1.0 / det;
  return pl;
}

// Depth of the triangle at the centre of pixel (ix0, iy0), and its gradient.
inline void depthAt(const Plane& pl, const SVert& v0, const SVert& v1, const SVert& v2, int ix0,
                    int iy0, double& z00, double& dzdx, double& dzdy) {
  const double cx = ix0 + 0.5 - v0.x, cy = iy0 + 0.5 - v0.y;  // centre of (ix0, iy0) rel. v0
  pl.gradient(v0.z, v1.z, v2.z, dzdx, dzdy);
  z00 = v0.z + rounded(dzdx * cx) + rounded(dzdy * cy);
}

// Depth at the first pixel of row offset dj (float; the pixels step from it in float).
inline float depthRowStart(double z00, double dzdy, double dj) {
  return float(z00 + rounded(dzdy * dj));
}

// Depth clamp to [0, 1], written to match SSE maxps/minps bit for bit.
inline float clampDepth(float z) {
  z = z > 0.0f ? z : 0.0f;
  return z < 1.0f ? z : 1.0f;
}

// Branch-free min/max (GCC tends to emit unpredictable branches for std::min/max here).
inline int64_t min64(int64_t a, int64_t b) {  // |a - b| < 2^63
  const int64_t d = b - a;
  return a + (d & (d >> 63));
}
inline int64_t max64(int64_t a, int64_t b) {
  const int64_t d = b - a;
  return b - (d & (d >> 63));
}

#if RASTER_SSE2
// Lane masks of a 4-bit coverage mask.
struct LaneMasks {
  alignas(16) uint32_t m[16][4];
  constexpr LaneMasks() : m() {
    for (int i = 0; i < 16; ++i)
      for (int l = 0; l < 4; ++l) m[i][l] = (i >> l) & 1 ? 0xFFFFFFFFu : 0u;
  }
};
constexpr LaneMasks kLaneMasks;
#endif

// Rasterises a counter-clockwise snapped triangle (area = area2(v0,v1,v2) > 0). Each row of the
// bounding box is walked in chunks of 4 pixels, stepping the 64-bit edge functions
// incrementally: the sign bits of E0|E1|E2 give the chunk's coverage mask (exact integer test).
// The item+depth fast path blends every chunk of the row with SSE2, whatever its mask: with the
// small triangles of item buffers, branching on coverage costs more in mispredictions than the
// few extra blends. The generic path skips empty chunks and stops after the row's span (a
// convex triangle covers a single span per row), then shades the covered pixels one by one.
// Without SSE2 the same masks are computed with scalar code (bit-identical results).
template <bool Fast, Shade S, bool Greater>
void rasterTriangle(const Ctx& c, const SVert& v0, const SVert& v1, const SVert& v2, int64_t area) {
  // Pixels whose centres lie in the snapped bounding box, clamped to viewport and scissor.
  const int64_t minX = min64(v0.X, min64(v1.X, v2.X)), maxX = max64(v0.X, max64(v1.X, v2.X));
  const int64_t minY = min64(v0.Y, min64(v1.Y, v2.Y)), maxY = max64(v0.Y, max64(v1.Y, v2.Y));
  const int ix0 = int(max64(c.x0, (minX - kHalf + kOne - 1) >> kSubpixelBits));
  const int ix1 = int(min64(c.x1, (maxX - kHalf) >> kSubpixelBits));
  const int iy0 = int(max64(c.y0, (minY - kHalf + kOne - 1) >> kSubpixelBits));
  const int iy1 = int(min64(c.y1, (maxY - kHalf) >> kSubpixelBits));
  if (ix0 > ix1 || iy0 > iy1) return;

  // Edge functions at the centre of pixel (ix0, iy0), E = A*(px-Xa) + B*(py-Ya), > 0 inside.
  // Edge k is opposite vertex k. Biased by -1 unless top-left, so "inside" is simply E >= 0,
  // i.e. the sign bit of (E0 | E1 | E2) is clear.
  const int64_t px = int64_t(ix0) * kOne + kHalf, py = int64_t(iy0) * kOne + kHalf;
  const SVert* ea[3] = {&v1, &v2, &v0};
  const SVert* eb[3] = {&v2, &v0, &v1};
  int64_t sx[3], sy[3], e0[3];
  for (int k = 0; k < 3; ++k) {
    const int64_t A = int64_t(ea[k]->Y) - eb[k]->Y, B = int64_t(eb[k]->X) - ea[k]->X;
    const int64_t topLeft = (A > 0) | ((A == 0) & (B < 0));
    sx[k] = A * kOne;
    sy[k] = B * kOne;
    e0[k] = A * (px - ea[k]->X) + B * (py - ea[k]->Y) - (1 - topLeft);
  }

  // Attribute planes from the exact (unsnapped) positions; snapped ones if those degenerate.
  const Plane pl = makePlane(v0, v1, v2, area);
  const double cx = ix0 + 0.5 - v0.x, cy = iy0 + 0.5 - v0.y;  // centre of (ix0, iy0) rel. v0
  double z00, dzdx, dzdy;
  depthAt(pl, v0, v1, v2, ix0, iy0, z00, dzdx, dzdy);
  const float fdzdx = float(dzdx);

  // Smooth shading: q = 1/w and s_k = lambda_k/w are affine in window space.
  double qx = 0, qy = 0, ax = 0, ay = 0, bx = 0, by = 0, q00 = 0, a00 = 0, b00 = 0;
  glm::vec4 c0(0.0f), c10(0.0f), c20(0.0f);
  if constexpr (S == Shade::Smooth) {
    pl.gradient(v0.q, v1.q, v2.q, qx, qy);
    pl.gradient(0.0, v1.q, 0.0, ax, ay);
    pl.gradient(0.0, 0.0, v2.q, bx, by);
    q00 = v0.q + qx * cx + qy * cy;
    a00 = ax * cx + ay * cy;
    b00 = bx * cx + by * cy;
    c0 = *v0.color;
    c10 = *v1.color - c0;
    c20 = *v2.color - c0;
  }

  // Locals, so that stores to the buffers cannot be assumed to alias the context.
  float* const depth = c.depth;
  uint32_t* const item = c.item;
  glm::vec4* const color = c.color;
  uint32_t* const hits = c.hits;
  const uint32_t id = c.id;
  const bool depthTest = c.depthTest, depthWrite = c.depthWrite;
  const int width = c.width;

  // Depth test: LESS, or GREATER for reversed depth.
  auto passes = [](float z, float stored) { return Greater ? stored < z : z < stored; };

  // One fragment at offset k = i - ix0 of row offset dj, buffer index idx.
  auto fragment = [&](size_t idx, float z, float fk, double dj) {
    if constexpr (Fast) {
      if (passes(z, depth[idx])) {
        depth[idx] = z;
        item[idx] = id;
      }
    } else {
      if (depthTest) {
        if (!passes(z, depth[idx])) return;
        if (depthWrite) depth[idx] = z;
      }
      if (item) item[idx] = id;
      if constexpr (S == Shade::Flat) {
        color[idx] = c.flat;
      } else if constexpr (S == Shade::Smooth) {
        const double q = q00 + qx * fk + qy * dj;
        const double la = (a00 + ax * fk + ay * dj) / q, lb = (b00 + bx * fk + by * dj) / q;
        color[idx] = c0 + float(la) * c10 + float(lb) * c20;
      }
      if (hits) ++hits[idx];
    }
  };

#if RASTER_SSE2
  // Edge k's values at lanes 0,1 (lo) and 2,3 (hi) of a chunk; per-row and per-chunk steps.
  // (Spelled out per edge so that they stay in registers even at -O2.)
  auto lanesLo = [&](int k) { return _mm_set_epi64x(e0[k] + sx[k], e0[k]); };
  auto lanesHi = [&](int k) { return _mm_set_epi64x(e0[k] + 3 * sx[k], e0[k] + 2 * sx[k]); };
  __m128i r0Lo = lanesLo(0), r1Lo = lanesLo(1), r2Lo = lanesLo(2);
  __m128i r0Hi = lanesHi(0), r1Hi = lanesHi(1), r2Hi = lanesHi(2);
  const __m128i y0 = _mm_set1_epi64x(sy[0]), y1 = _mm_set1_epi64x(sy[1]), y2 = _mm_set1_epi64x(sy[2]);
  const __m128i x0 = _mm_set1_epi64x(4 * sx[0]), x1 = _mm_set1_epi64x(4 * sx[1]);
  const __m128i x2 = _mm_set1_epi64x(4 * sx[2]);
  const __m128 dz4 = _mm_set1_ps(fdzdx), zero4 = _mm_setzero_ps(), one4 = _mm_set1_ps(1.0f);
  const __m128 four4 = _mm_set1_ps(4.0f), lanes4 = _mm_set_ps(3.0f, 2.0f, 1.0f, 0.0f);
  const __m128i idv = _mm_set1_epi32(int(id));
#else
  int64_t row[3] = {e0[0], e0[1], e0[2]};
#endif

  size_t rowBase = size_t(iy0) * size_t(width) + size_t(ix0);
  for (int j = iy0; j <= iy1; ++j, rowBase += size_t(width)) {
    const double dj = j - iy0;
    const float zr = depthRowStart(z00, dzdy, dj);  // depth at pixel ix0 of this row
    bool seen = false;
#if RASTER_SSE2
    __m128i e0Lo = r0Lo, e1Lo = r1Lo, e2Lo = r2Lo, e0Hi = r0Hi, e1Hi = r1Hi, e2Hi = r2Hi;
    r0Lo = _mm_add_epi64(r0Lo, y0), r1Lo = _mm_add_epi64(r1Lo, y1), r2Lo = _mm_add_epi64(r2Lo, y2);
    r0Hi = _mm_add_epi64(r0Hi, y0), r1Hi = _mm_add_epi64(r1Hi, y1), r2Hi = _mm_add_epi64(r2Hi, y2);
    const __m128 zr4 = _mm_set1_ps(zr);
    __m128 fk4 = lanes4;
#else
    int64_t e[3] = {row[0], row[1], row[2]};
    row[0] += sy[0], row[1] += sy[1], row[2] += sy[2];
#endif
    for (int i = ix0; i <= ix1; i += 4) {
      const int valid = 0xF >> int(max64(0, i + 3 - ix1));  // lanes up to ix1
#if RASTER_SSE2
      // Sign bits of E0|E1|E2 of the 4 pixels = the outside ones.
      const __m128i oLo = _mm_or_si128(_mm_or_si128(e0Lo, e1Lo), e2Lo);
      const __m128i oHi = _mm_or_si128(_mm_or_si128(e0Hi, e1Hi), e2Hi);
      const int out = _mm_movemask_pd(_mm_castsi128_pd(oLo)) | _mm_movemask_pd(_mm_castsi128_pd(oHi)) << 2;
      const int mask = ~out & valid;
      e0Lo = _mm_add_epi64(e0Lo, x0), e1Lo = _mm_add_epi64(e1Lo, x1), e2Lo = _mm_add_epi64(e2Lo, x2);
      e0Hi = _mm_add_epi64(e0Hi, x0), e1Hi = _mm_add_epi64(e1Hi, x1), e2Hi = _mm_add_epi64(e2Hi, x2);
      const __m128 fk = fk4;
      fk4 = _mm_add_ps(fk4, four4);
      if (!Fast && !mask) {
        if (seen) break;
        continue;
      }
      seen = true;
      const __m128 z = _mm_min_ps(_mm_max_ps(_mm_add_ps(zr4, rounded(_mm_mul_ps(dz4, fk))), zero4), one4);
      if constexpr (Fast) {
        if (i + 3 < width) {  // blend the 4 pixels at once
          float* d = depth + rowBase + size_t(i - ix0);
          uint32_t* it = item + rowBase + size_t(i - ix0);
          const __m128 dOld = _mm_loadu_ps(d);
          const __m128 pass = _mm_and_ps(Greater ? _mm_cmplt_ps(dOld, z) : _mm_cmplt_ps(z, dOld),
                                         _mm_load_ps(reinterpret_cast<const float*>(kLaneMasks.m[mask])));
          _mm_storeu_ps(d, _mm_or_ps(_mm_and_ps(pass, z), _mm_andnot_ps(pass, dOld)));
          const __m128i p = _mm_castps_si128(pass);
          const __m128i iOld = _mm_loadu_si128(reinterpret_cast<const __m128i*>(it));
          _mm_storeu_si128(reinterpret_cast<__m128i*>(it),
                           _mm_or_si128(_mm_and_si128(p, idv), _mm_andnot_si128(p, iOld)));
          continue;
        }
      }
      alignas(16) float zs[4];
      _mm_store_ps(zs, z);
#else
      int mask = 0;
      float zs[4];
      for (int l = 0; l < 4; ++l) {
        mask |= int((e[0] | e[1] | e[2]) >= 0) << l;
        zs[l] = clampDepth(zr + rounded(fdzdx * float(i + l - ix0)));
        e[0] += sx[0], e[1] += sx[1], e[2] += sx[2];
      }
      mask &= valid;
      if (!mask) {
        if (seen) break;
        continue;
      }
      seen = true;
#endif
      for (int m = mask; m; m &= m - 1) {
        const int l = __builtin_ctz(unsigned(m));
        fragment(rowBase + size_t(i - ix0 + l), zs[l], float(i - ix0 + l), dj);
      }
    }
  }
}

// Orients (or culls) a snapped triangle and rasterises it.
template <bool Fast, Shade S, bool Greater>
inline void drawSnapped(const Ctx& c, const SVert& v0, const SVert& v1, const SVert& v2) {
  const int64_t a = area2(v0, v1, v2);
  if (a > 0)
    rasterTriangle<Fast, S, Greater>(c, v0, v1, v2, a);
  else if (a < 0 && !c.cullBack)
    rasterTriangle<Fast, S, Greater>(c, v0, v2, v1, -a);
}

#if RASTER_SSE2
// SSE2 min/max of 32-bit lanes (pminsd/pmaxsd are SSE4.1).
inline __m128i minEpi32(__m128i a, __m128i b) {
  const __m128i gt = _mm_cmpgt_epi32(a, b);
  return _mm_or_si128(_mm_and_si128(gt, b), _mm_andnot_si128(gt, a));
}
inline __m128i maxEpi32(__m128i a, __m128i b) {
  const __m128i gt = _mm_cmpgt_epi32(a, b);
  return _mm_or_si128(_mm_and_si128(gt, a), _mm_andnot_si128(gt, b));
}

// The item+depth path's setup for unclipped triangles whose vertex spans are below kSmallSpan =
// 2^14 in fixed point (64 pixels): nearly all of them with the fine meshes of a hemicube.
// Coordinates relative to a vertex then fit in 16 bits, so that pmaddwd gives the edge
// functions of the three edges at once, and the edge functions over the bounding box (plus
// the 3 columns a chunk may reach beyond it) stay below 2^29.1 in magnitude: 32-bit lanes,
// 4 pixels per register instead of 2. Boxes of at most 4 x kSmallRows pixel centres (most
// triangles of a fine mesh) get their whole coverage first, branch-free, and the depth plane
// only if some centre is covered; larger ones walk rows of 4-pixel chunks like rasterTriangle.
// Results are those of rasterTriangle<true, ...> bit for bit: the integer edge tests are
// exact, the chunks are the same (so are the pixels rewritten beyond the box), and the depth
// values come from the same sequence of IEEE operations.
constexpr int kSmallRows = 4;
constexpr int32_t kSmallSpan = 1 << 14;

// Per-draw constants of fastTriangle.
struct FastCtx {
  __m128i clipLo, clipHi;  // (x0, y0, 0, 0), (x1, y1, 0, 0): pixel range of viewport & scissor
  int width;
};

// One unclipped triangle (vertex indices i0, i1, i2) of the item+depth path: bounding box,
// orientation, then the small-box or chunked setup above, or rasterTriangle for large spans.
// (Not inlined: the triangle loop stays small, and this measures a little faster.)
template <bool Greater>
__attribute__((noinline)) void fastTriangle(Ctx& c, const FastCtx& fc, const glm::vec4* win,
                                            const glm::ivec2* fixed, uint32_t i0, uint32_t i1,
                                            uint32_t i2, uint32_t id) {
  const __m128i p0 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(fixed + i0));  // X, Y, 0, 0
  const __m128i p1 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(fixed + i1));
  const __m128i p2 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(fixed + i2));
  // Pixels whose centres lie in the snapped bounding box (as in rasterTriangle), lanes x, y.
  const __m128i mn = minEpi32(p0, minEpi32(p1, p2)), mx = maxEpi32(p0, maxEpi32(p1, p2));
  const __m128i lo = maxEpi32(_mm_srai_epi32(_mm_add_epi32(mn, _mm_set1_epi32(kOne - 1 - kHalf)),
                                             kSubpixelBits), fc.clipLo);
  const __m128i hi = minEpi32(_mm_srai_epi32(_mm_sub_epi32(mx, _mm_set1_epi32(kHalf)),
                                             kSubpixelBits), fc.clipHi);
  if (_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(lo, hi))) & 3) return;  // no centre
  const __m128i dims = _mm_sub_epi32(hi, lo);  // columns - 1, rows - 1
  // Twice the signed area (exact in 64 bits).
  const int64_t X0 = fixed[i0].x, Y0 = fixed[i0].y;
  const int64_t X1 = fixed[i1].x - X0, Y1 = fixed[i1].y - Y0;
  const int64_t X2 = fixed[i2].x - X0, Y2 = fixed[i2].y - Y0;
  const int64_t signedArea = X1 * Y2 - X2 * Y1;
  if (signedArea == 0 || (signedArea < 0 && c.cullBack)) return;
  const bool flip = signedArea < 0;  // clockwise: rasterise (v0, v2, v1)
  const int64_t area = flip ? -signedArea : signedArea;
  const uint32_t j1 = flip ? i2 : i1, j2 = flip ? i1 : i2;

  const int ix0 = _mm_cvtsi128_si32(lo), iy0 = _mm_cvtsi128_si32(_mm_shuffle_epi32(lo, 0x55));
  const int colsM1 = _mm_cvtsi128_si32(dims);
  const int rowsM1 = _mm_cvtsi128_si32(_mm_shuffle_epi32(dims, 0x55));
  const __m128i spanOk = _mm_cmplt_epi32(_mm_sub_epi32(mx, mn), _mm_set1_epi32(kSmallSpan));
  if ((_mm_movemask_ps(_mm_castsi128_ps(spanOk)) & 3) != 3 ||
      ix0 + (colsM1 | 3) >= fc.width) {  // too large, or the last 4-pixel chunk leaves the row
    c.id = id;
    rasterTriangle<true, Shade::None, Greater>(c, makeSVert(win[i0], fixed[i0], nullptr),
                                               makeSVert(win[j1], fixed[j1], nullptr),
                                               makeSVert(win[j2], fixed[j2], nullptr), area);
    return;
  }

  // Edge functions at the centres of pixels ix0..ix0+3 of row iy0, with pmaddwd on 16-bit
  // coordinates relative to v0: r1 = v1 - v0, r2 = v2 - v0, rc = centre of (ix0, iy0) - v0.
  // Edge k (opposite vertex k) runs from a = (1, 2, 0)[k] to b = (2, 0, 1)[k] of the triangle
  // as given; pair k of the vectors below belongs to edge k (pair 3 is zero). For a clockwise
  // triangle, (A, B) and so E change sign: the edges of (v0, v2, v1), exactly.
  const __m128i centre = _mm_add_epi32(_mm_slli_epi32(lo, kSubpixelBits), _mm_set1_epi32(kHalf));
  const __m128i v = _mm_packs_epi32(
      _mm_unpacklo_epi64(_mm_sub_epi32(p1, p0), _mm_sub_epi32(p2, p0)),
      _mm_unpacklo_epi64(_mm_sub_epi32(centre, p0), _mm_setzero_si128()));
  const __m128i ra = _mm_shuffle_epi32(v, _MM_SHUFFLE(3, 3, 1, 0));  // r1, r2, 0
  const __m128i rb = _mm_shuffle_epi32(v, _MM_SHUFFLE(3, 0, 3, 1));  // r2, 0, r1
  const __m128i rc = _mm_shuffle_epi32(v, _MM_SHUFFLE(3, 2, 2, 2));
  const __m128i dv = _mm_sub_epi16(rb, ra);  // (Xb - Xa, Yb - Ya)
  // (A, B) = (Ya - Yb, Xb - Xa): swap each pair, negate its first element (both if flipped).
  const __m128i neg = _mm_xor_si128(_mm_setr_epi16(-1, 0, -1, 0, -1, 0, -1, 0),
                                    _mm_set1_epi16(int16_t(-int(flip))));
  const __m128i sw = _mm_shufflehi_epi16(_mm_shufflelo_epi16(dv, _MM_SHUFFLE(2, 3, 0, 1)),
                                         _MM_SHUFFLE(2, 3, 0, 1));
  const __m128i ab = _mm_sub_epi16(_mm_xor_si128(sw, neg), neg);
  const __m128i o = _mm_sub_epi16(rc, ra);  // (px - Xa, py - Ya)
  const __m128i sx = _mm_madd_epi16(ab, _mm_setr_epi16(kOne, 0, kOne, 0, kOne, 0, kOne, 0));
  const __m128i sy = _mm_madd_epi16(ab, _mm_setr_epi16(0, kOne, 0, kOne, 0, kOne, 0, kOne));
  // Bias -1 unless top-left (A > 0, or A == 0 and B < 0), so that "inside" is E >= 0.
  const __m128i zero = _mm_setzero_si128();
  const __m128i topLeft = _mm_or_si128(
      _mm_cmpgt_epi32(sx, zero), _mm_and_si128(_mm_cmpeq_epi32(sx, zero), _mm_cmpgt_epi32(zero, sy)));
  const __m128i bias = _mm_andnot_si128(topLeft, _mm_set1_epi32(-1));
  const __m128i colOffset = _mm_setr_epi16(0, 0, kOne, 0, 2 * kOne, 0, 3 * kOne, 0);
  auto edge = [&](auto sel) {  // lane l: edge function at column ix0 + l, row iy0
    constexpr int s = decltype(sel)::value;
    return _mm_add_epi32(_mm_madd_epi16(_mm_shuffle_epi32(ab, s),
                                        _mm_add_epi16(_mm_shuffle_epi32(o, s), colOffset)),
                         _mm_shuffle_epi32(bias, s));
  };
  __m128i e0 = edge(std::integral_constant<int, 0x00>());
  __m128i e1 = edge(std::integral_constant<int, 0x55>());
  __m128i e2 = edge(std::integral_constant<int, 0xAA>());
  const __m128i s0 = _mm_shuffle_epi32(sy, 0x00), s1 = _mm_shuffle_epi32(sy, 0x55);
  const __m128i s2 = _mm_shuffle_epi32(sy, 0xAA);
  // Depth plane, as in rasterTriangle (vertices v0, v1, v2 in counter-clockwise order).
  double z00, dzdx, dzdy;
  auto depthPlane = [&] {
    const SVert v0 = makeSVert(win[i0], fixed[i0], nullptr);
    const SVert v1 = makeSVert(win[j1], fixed[j1], nullptr);
    const SVert v2 = makeSVert(win[j2], fixed[j2], nullptr);
    depthAt(makePlane(v0, v1, v2, area), v0, v1, v2, ix0, iy0, z00, dzdx, dzdy);
  };
  const __m128 zero4 = _mm_setzero_ps(), one4 = _mm_set1_ps(1.0f);
  const __m128i idv = _mm_set1_epi32(int(id));
  float* const d = c.depth + size_t(iy0) * size_t(c.width) + size_t(ix0);
  uint32_t* const it = c.item + size_t(iy0) * size_t(c.width) + size_t(ix0);
  // Depth test and write of the 4 pixels at d[off], it[off] (lanes of `in` all ones).
  auto blend = [&](size_t off, __m128 z, __m128i in) {
    const __m128 dOld = _mm_loadu_ps(d + off);
    const __m128 pass = _mm_and_ps(Greater ? _mm_cmplt_ps(dOld, z) : _mm_cmplt_ps(z, dOld),
                                   _mm_castsi128_ps(in));
    _mm_storeu_ps(d + off, _mm_or_ps(_mm_and_ps(pass, z), _mm_andnot_ps(pass, dOld)));
    const __m128i p = _mm_castps_si128(pass);
    const __m128i iOld = _mm_loadu_si128(reinterpret_cast<const __m128i*>(it + off));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(it + off),
                     _mm_or_si128(_mm_and_si128(p, idv), _mm_andnot_si128(p, iOld)));
  };
  auto clamp01 = [&](__m128 z) { return _mm_min_ps(_mm_max_ps(z, zero4), one4); };
  const __m128 lanes4 = _mm_set_ps(3.0f, 2.0f, 1.0f, 0.0f);

  if (colsM1 < 4 && rowsM1 < kSmallRows) {
    // One chunk per row: coverage of the whole box first, branch-free (lanes beyond the box
    // masked), then the depth plane only if some centre is covered.
    const __m128i colValid = _mm_cmpgt_epi32(_mm_shuffle_epi32(dims, 0x00), _mm_setr_epi32(-1, 0, 1, 2));
    const __m128i rowsM1v = _mm_shuffle_epi32(dims, 0x55);
    __m128i in[kSmallRows];
    __m128i any = zero;
    for (int r = 0; r < kSmallRows; ++r) {
      const __m128i out = _mm_srai_epi32(_mm_or_si128(_mm_or_si128(e0, e1), e2), 31);
      const __m128i valid = _mm_and_si128(colValid, _mm_cmpgt_epi32(rowsM1v, _mm_set1_epi32(r - 1)));
      in[r] = _mm_andnot_si128(out, valid);
      any = _mm_or_si128(any, in[r]);
      e0 = _mm_add_epi32(e0, s0), e1 = _mm_add_epi32(e1, s1), e2 = _mm_add_epi32(e2, s2);
    }
    if (!_mm_movemask_epi8(any)) return;
    depthPlane();
    // Row r starts at depthRowStart(.., r) (cvtpd2ps rounds like float(double)), its pixel l
    // at clamp(start + float(dzdx)*l).
    const __m128d zz = _mm_set1_pd(z00), dy = _mm_set1_pd(dzdy);
    const __m128 zr = _mm_movelh_ps(
        _mm_cvtpd_ps(_mm_add_pd(zz, rounded(_mm_mul_pd(dy, _mm_set_pd(1.0, 0.0))))),
        _mm_cvtpd_ps(_mm_add_pd(zz, rounded(_mm_mul_pd(dy, _mm_set_pd(3.0, 2.0))))));
    const __m128 dz = rounded(_mm_mul_ps(_mm_set1_ps(float(dzdx)), lanes4));
    auto rowZ = [&](__m128 start) { return clamp01(_mm_add_ps(start, dz)); };
    const size_t w = size_t(c.width);
    blend(0, rowZ(_mm_shuffle_ps(zr, zr, 0x00)), in[0]);
    if (rowsM1 > 0) blend(w, rowZ(_mm_shuffle_ps(zr, zr, 0x55)), in[1]);
    if (rowsM1 > 1) blend(2 * w, rowZ(_mm_shuffle_ps(zr, zr, 0xAA)), in[2]);
    if (rowsM1 > 2) blend(3 * w, rowZ(_mm_shuffle_ps(zr, zr, 0xFF)), in[3]);
    return;
  }

  // Rows of up to 16 chunks of 4 pixels; every chunk of the box is blended (masked), as in
  // rasterTriangle.
  depthPlane();
  const __m128 dz4 = _mm_set1_ps(float(dzdx)), four4 = _mm_set1_ps(4.0f);
  const __m128i c0 = _mm_shuffle_epi32(sx, 0x00), c1 = _mm_shuffle_epi32(sx, 0x55);
  const __m128i c2 = _mm_shuffle_epi32(sx, 0xAA);
  const __m128i x0 = _mm_slli_epi32(c0, 2), x1 = _mm_slli_epi32(c1, 2), x2 = _mm_slli_epi32(c2, 2);
  const __m128i colsM1v = _mm_shuffle_epi32(dims, 0x00);
  const int chunks = (colsM1 >> 2) + 1;
  size_t rowOff = 0;
  for (int r = 0; r <= rowsM1; ++r, rowOff += size_t(c.width)) {
    const __m128 zr4 = _mm_set1_ps(depthRowStart(z00, dzdy, double(r)));
    __m128i f0 = e0, f1 = e1, f2 = e2;
    e0 = _mm_add_epi32(e0, s0), e1 = _mm_add_epi32(e1, s1), e2 = _mm_add_epi32(e2, s2);
    __m128 fk = lanes4;
    __m128i col = _mm_setr_epi32(-1, 0, 1, 2);  // column - 1 of each lane
    for (int k = 0; k < chunks; ++k) {
      const __m128i out = _mm_srai_epi32(_mm_or_si128(_mm_or_si128(f0, f1), f2), 31);
      const __m128i in = _mm_andnot_si128(out, _mm_cmpgt_epi32(colsM1v, col));
      blend(rowOff + size_t(4 * k), clamp01(_mm_add_ps(zr4, rounded(_mm_mul_ps(dz4, fk)))), in);
      f0 = _mm_add_epi32(f0, x0), f1 = _mm_add_epi32(f1, x1), f2 = _mm_add_epi32(f2, x2);
      fk = _mm_add_ps(fk, four4);
      col = _mm_add_epi32(col, _mm_set1_epi32(4));
    }
  }
}
#endif

// A polygon vertex during clipping. Clipping works in double precision: a near-plane cut
// subtracts nearly equal w values, and in float the cut points of one triangle can come out
// in the wrong order far out in the guard band, which turned convex polygons concave and lost
// whole fan triangles (regression test NearPlaneCutNearTheEyeStaysConvex).
struct CVert {
  glm::dvec4 pos;
  glm::vec4 col;
  uint32_t src;  // original vertex index, or kGenerated
};

// planeDist in double, for the clipper.
inline double planeDistD(const glm::dvec4& v, int p, const Frame& f) {
  switch (p) {
    case 0: return v.z + double(f.nearW) * v.w;
    case 1: return v.w - v.z;
    case 2: return v.x + double(f.gx) * v.w;
    case 3: return double(f.gx) * v.w - v.x;
    case 4: return v.y + double(f.gy) * v.w;
    default: return double(f.gy) * v.w - v.y;
  }
}

// Clip space (double) -> (x_w, y_w, depth, 1/w), for vertices made by clipping.
inline glm::vec4 projectD(const glm::dvec4& v, const Frame& f) {
  const double q = 1.0 / v.w;
  return glm::vec4(float((v.x * q + 1.0) * f.halfW), float((v.y * q + 1.0) * f.halfH),
                   float(v.z * q * f.zScale + f.zBias), float(q));
}

// Intersection of edge (in, out) with plane p. Always computed from the inside vertex, so an
// edge shared by two triangles is cut at bit-identical points whatever its direction.
inline CVert intersect(const CVert& in, double din, const CVert& out, double dout, int p,
                       const Frame& f) {
  const double t = din / (din - dout);
  CVert r;
  r.pos = in.pos + t * (out.pos - in.pos);
  r.col = in.col + float(t) * (out.col - in.col);
  r.src = kGenerated;
  switch (p) {  // put the vertex exactly on the plane
    case 0: r.pos.z = -(double(f.nearW) * r.pos.w); break;
    case 1: r.pos.z = r.pos.w; break;
    case 2: r.pos.x = -(double(f.gx) * r.pos.w); break;
    case 3: r.pos.x = double(f.gx) * r.pos.w; break;
    case 4: r.pos.y = -(double(f.gy) * r.pos.w); break;
    default: r.pos.y = double(f.gy) * r.pos.w; break;
  }
  return r;
}

// Clips triangle (a, b, c) against near, far and guard-band planes and draws the fan.
template <bool Fast, Shade S, bool Greater>
void clipAndDraw(const Ctx& c, const Frame& f, const glm::vec4* clip, const glm::vec4* win,
                 const glm::ivec2* fixed, const uint16_t* codes, const glm::vec4* colors,
                 const uint32_t (&vi)[3]) {
  CVert bufA[kMaxPoly], bufB[kMaxPoly];
  CVert* poly = bufA;
  CVert* next = bufB;
  int n = 3;
  for (int k = 0; k < 3; ++k) {
    poly[k].pos = glm::dvec4(clip[vi[k]]);
    poly[k].col = (S == Shade::Smooth) ? colors[vi[k]] : glm::vec4(0.0f);
    poly[k].src = vi[k];
  }
  // Every plane is tested (not only those flagged by the triangle's outcodes) so that adjacent
  // triangles cut their shared edge identically even after rounding in earlier planes.
  for (int p = 0; p < kPlaneCount; ++p) {
    double d[kMaxPoly];
    bool anyOut = false;
    for (int k = 0; k < n; ++k) {
      d[k] = planeDistD(poly[k].pos, p, f);
      anyOut |= !(d[k] >= 0.0);
    }
    if (!anyOut) continue;
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const int k1 = k + 1 == n ? 0 : k + 1;
      const bool in0 = d[k] >= 0.0, in1 = d[k1] >= 0.0;
      if (m + 2 > kMaxPoly) return;  // impossible for finite input
      if (in0) next[m++] = poly[k];
      if (in0 != in1)
        next[m++] = in0 ? intersect(poly[k], d[k], poly[k1], d[k1], p, f)
                        : intersect(poly[k1], d[k1], poly[k], d[k], p, f);
    }
    std::swap(poly, next);
    n = m;
    if (n < 3) return;
  }

  // Original vertices that survived use the vertex stage's values, exactly as the unclipped
  // triangles sharing them do (the outcodes and the clipper agree on inside/outside).
  SVert sv[kMaxPoly];
  for (int k = 0; k < n; ++k) {
    const uint32_t s = poly[k].src;
    if (s != kGenerated && !(codes[s] & kClipBits)) {
      sv[k] = makeSVert(win[s], fixed[s], &poly[k].col);
      continue;
    }
    const glm::vec4 w = projectD(poly[k].pos, f);
    const float lim = kGuardPixels + 1.0f;
    if (!(std::fabs(w.x) <= lim && std::fabs(w.y) <= lim && std::fabs(w.z) <= 2.0f && w.w > 0.0f &&
          w.w <= FLT_MAX))
      return;  // NaN input, or the zero vector as a vertex
    sv[k] = makeSVert(w, &poly[k].col);
  }
  // Fan from vertex 0; the polygon's orientation decides culling, and fan slivers whose
  // orientation flipped through snapping are dropped.
  int64_t fan[kMaxPoly];
  int64_t total = 0;
  for (int k = 1; k + 1 < n; ++k) total += fan[k] = area2(sv[0], sv[k], sv[k + 1]);
  if (total == 0 || (total < 0 && c.cullBack)) return;
  for (int k = 1; k + 1 < n; ++k) {
    if (total > 0 && fan[k] > 0)
      rasterTriangle<Fast, S, Greater>(c, sv[0], sv[k], sv[k + 1], fan[k]);
    else if (total < 0 && fan[k] < 0)
      rasterTriangle<Fast, S, Greater>(c, sv[0], sv[k + 1], sv[k], -fan[k]);
  }
}

// Fills n 32-bit words (vectorised by hand: -O2 does not vectorise std::fill of a float).
void fill32(uint32_t* p, size_t n, uint32_t value) {
  size_t i = 0;
#if RASTER_SSE2
  const __m128i v = _mm_set1_epi32(int(value));
  for (; i + 16 <= n; i += 16) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i + 4), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i + 8), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i + 12), v);
  }
#endif
  for (; i < n; ++i) p[i] = value;
}

// Whether all n indices are below `limit` (vertexCount, >= 1).
bool indicesBelow(const uint32_t* idx, size_t n, size_t limit) {
  if (limit > 0xFFFFFFFFu) return true;
  const uint32_t last = uint32_t(limit - 1);  // largest valid index
  size_t i = 0;
#if RASTER_SSE2
  // Unsigned compares through signed ones of values offset by 2^31; four independent
  // accumulators of "some index > last".
  const __m128i flip = _mm_set1_epi32(int(0x80000000u));
  const __m128i bound = _mm_xor_si128(_mm_set1_epi32(int(last)), flip);
  __m128i bad0 = _mm_setzero_si128(), bad1 = bad0, bad2 = bad0, bad3 = bad0;
  auto over = [&](size_t k) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(idx + k));
    return _mm_cmpgt_epi32(_mm_xor_si128(x, flip), bound);
  };
  for (; i + 16 <= n; i += 16) {
    bad0 = _mm_or_si128(bad0, over(i));
    bad1 = _mm_or_si128(bad1, over(i + 4));
    bad2 = _mm_or_si128(bad2, over(i + 8));
    bad3 = _mm_or_si128(bad3, over(i + 12));
  }
  for (; i + 4 <= n; i += 4) bad0 = _mm_or_si128(bad0, over(i));
  if (_mm_movemask_epi8(_mm_or_si128(_mm_or_si128(bad0, bad1), _mm_or_si128(bad2, bad3))))
    return false;
#endif
  uint32_t m = 0;
  for (; i < n; ++i) m = std::max(m, idx[i]);
  return m <= last;
}

// The vertex indices of triangle t (non-indexed drawing: 3t, 3t+1, 3t+2).
inline void triangleVertices(const uint32_t* indices, size_t t, uint32_t (&vi)[3]) {
  for (int k = 0; k < 3; ++k) vi[k] = indices ? indices[3 * t + k] : uint32_t(3 * t + k);
}

// The triangle loop: trivial reject, fast unclipped setup or clipping.
template <bool Fast, Shade S, bool Greater>
void drawAll(Ctx& c, const Frame& f, const glm::vec4* clip, const uint32_t* indices,
             size_t triangleCount, const uint32_t* ids, const glm::vec4* colors,
             const glm::vec4* win, const glm::ivec2* fixed, const uint16_t* codes) {
  for (size_t t = 0; t < triangleCount; ++t) {
    uint32_t vi[3];
    triangleVertices(indices, t, vi);
    const uint32_t o0 = codes[vi[0]], o1 = codes[vi[1]], o2 = codes[vi[2]];
    if (o0 & o1 & o2) continue;  // entirely outside one plane
    c.id = ids ? ids[t] : uint32_t(t);
    if constexpr (S == Shade::Flat) c.flat = colors[vi[2]];  // provoking vertex: the last
    if (((o0 | o1 | o2) & kClipBits) == 0) {
      const bool sm = S == Shade::Smooth;
      drawSnapped<Fast, S, Greater>(c, makeSVert(win[vi[0]], fixed[vi[0]], sm ? colors + vi[0] : nullptr),
                           makeSVert(win[vi[1]], fixed[vi[1]], sm ? colors + vi[1] : nullptr),
                           makeSVert(win[vi[2]], fixed[vi[2]], sm ? colors + vi[2] : nullptr));
    } else {
      clipAndDraw<Fast, S, Greater>(c, f, clip, win, fixed, codes, colors, vi);
    }
  }
}

#if RASTER_SSE2
// The item+depth path's triangle loop: the pipeline of drawAll<true, ...>, with the unclipped
// triangles set up by fastTriangle straight from the vertex stage's arrays.
template <bool Greater>
void drawAllFast(Ctx& c, const Frame& f, const glm::vec4* clip, const uint32_t* indices,
                 size_t triangleCount, const uint32_t* ids, const glm::vec4* win,
                 const glm::ivec2* fixed, const uint16_t* codes) {
  FastCtx fc;
  fc.clipLo = _mm_setr_epi32(c.x0, c.y0, 0, 0);
  fc.clipHi = _mm_setr_epi32(c.x1, c.y1, 0, 0);
  fc.width = c.width;
  for (size_t t = 0; t < triangleCount; ++t) {
    uint32_t vi[3];
    triangleVertices(indices, t, vi);
    const uint32_t o0 = codes[vi[0]], o1 = codes[vi[1]], o2 = codes[vi[2]];
    if (o0 & o1 & o2) continue;  // entirely outside one plane
    const uint32_t id = ids ? ids[t] : uint32_t(t);
    if (((o0 | o1 | o2) & kClipBits) == 0) {
      fastTriangle<Greater>(c, fc, win, fixed, vi[0], vi[1], vi[2], id);
    } else {
      c.id = id;
      clipAndDraw<true, Shade::None, Greater>(c, f, clip, win, fixed, codes, nullptr, vi);
    }
  }
}
#endif

// Picks the instantiation of the pipeline for the path, the shading and the depth function.
template <bool Greater>
void dispatch(bool fast, Shade shade, Ctx& c, const Frame& f, const glm::vec4* clip,
              const uint32_t* indices, size_t count, const uint32_t* ids, const glm::vec4* colors,
              const glm::vec4* win, const glm::ivec2* fixed, const uint16_t* codes) {
  if (fast)
#if RASTER_SSE2
    drawAllFast<Greater>(c, f, clip, indices, count, ids, win, fixed, codes);
#else
    drawAll<true, Shade::None, Greater>(c, f, clip, indices, count, ids, colors, win, fixed, codes);
#endif
  else if (shade == Shade::None)
    drawAll<false, Shade::None, Greater>(c, f, clip, indices, count, ids, colors, win, fixed, codes);
  else if (shade == Shade::Flat)
    drawAll<false, Shade::Flat, Greater>(c, f, clip, indices, count, ids, colors, win, fixed, codes);
  else
    drawAll<false, Shade::Smooth, Greater>(c, f, clip, indices, count, ids, colors, win, fixed, codes);
}

}  // namespace

Target::Target(int w, int h, bool withItem, bool withColor) {
  if (withItem) item.resize(1);
  if (withColor) color.resize(1);
  resize(w, h);
}

void Target::resize(int w, int h) {
  if (w < 1 || h < 1 || w > kMaxSize || h > kMaxSize)
    throw std::invalid_argument("raster::Target: size must be within 1..kMaxSize");
  width = w;
  height = h;
  const size_t n = size_t(w) * size_t(h);
  depth.assign(n, 1.0f);
  if (!item.empty()) item.assign(n, kNoItem);
  if (!color.empty()) color.assign(n, glm::vec4(0.0f));
  if (!hits.empty()) hits.assign(n, 0u);
}

void Target::clearDepth(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  fill32(reinterpret_cast<uint32_t*>(depth.data()), depth.size(), bits);
}
void Target::clearItem(uint32_t value) { fill32(item.data(), item.size(), value); }
void Target::clearColor(const glm::vec4& value) { std::fill(color.begin(), color.end(), value); }

void Target::clear() {
  clearDepth();
  clearItem();
  clearColor();
  std::fill(hits.begin(), hits.end(), 0u);
}

void transform(const glm::mat4& mvp, const glm::vec3* positions, size_t count, glm::vec4* clip) {
  const glm::vec4 c0 = mvp[0], c1 = mvp[1], c2 = mvp[2], c3 = mvp[3];
  for (size_t i = 0; i < count; ++i) {
    const glm::vec3 p = positions[i];
    clip[i] = c0 * p.x + c1 * p.y + c2 * p.z + c3;
  }
}

void transform(const glm::mat4& mvp, const std::vector<glm::vec3>& positions,
               std::vector<glm::vec4>& clip) {
  clip.resize(positions.size());
  transform(mvp, positions.data(), positions.size(), clip.data());
}

void drawTriangles(Target& target, const State& state, const glm::vec4* clip, size_t vertexCount,
                   const uint32_t* indices, size_t triangleCount, const uint32_t* ids,
                   const glm::vec4* colors) {
  if (triangleCount == 0 || vertexCount == 0 || target.width < 1 || target.height < 1) return;
  const size_t pixels = size_t(target.width) * size_t(target.height);
  if (target.depth.size() != pixels || (!target.item.empty() && target.item.size() != pixels) ||
      (!target.color.empty() && target.color.size() != pixels) ||
      (!target.hits.empty() && target.hits.size() != pixels))
    throw std::invalid_argument("raster::drawTriangles: target buffers do not match its size");
  if (indices) {
    if (!indicesBelow(indices, 3 * triangleCount, vertexCount))
      throw std::out_of_range("raster::drawTriangles: vertex index out of range");
  } else {
    triangleCount = std::min(triangleCount, vertexCount / 3);
  }

  Ctx c{};
  c.x0 = 0, c.y0 = 0, c.x1 = target.width - 1, c.y1 = target.height - 1;
  if (state.scissorTest) {
    c.x0 = std::max(c.x0, state.scissor.x);
    c.y0 = std::max(c.y0, state.scissor.y);
    c.x1 = std::min<int64_t>(c.x1, int64_t(state.scissor.x) + state.scissor.width - 1);
    c.y1 = std::min<int64_t>(c.y1, int64_t(state.scissor.y) + state.scissor.height - 1);
    if (c.x0 > c.x1 || c.y0 > c.y1) return;
  }
  const bool wantColor = state.shade != Shade::None && colors && !target.color.empty();
  c.depth = target.depth.data();
  c.item = target.item.empty() ? nullptr : target.item.data();
  c.color = wantColor ? target.color.data() : nullptr;
  c.hits = target.hits.empty() ? nullptr : target.hits.data();
  c.width = target.width;
  c.cullBack = state.cull == Cull::Back;
  c.depthTest = state.depthTest;
  c.depthWrite = state.depthWrite;

  Frame f;
  f.halfW = 0.5f * float(target.width);
  f.halfH = 0.5f * float(target.height);
  f.gx = kGuardPixels / f.halfW - 1.0f;
  f.gy = kGuardPixels / f.halfH - 1.0f;
  const bool zeroToOne = state.clipDepth == ClipDepth::ZeroToOne;
  f.nearW = zeroToOne ? 0.0f : 1.0f;
  f.zScale = zeroToOne ? 1.0f : 0.5f;
  f.zBias = zeroToOne ? 0.0f : 0.5f;

  // Vertex stage: outcodes and window coordinates of every vertex, once per draw.
  auto& win = target.scratch.window;
  auto& fixed = target.scratch.fixed;
  auto& codes = target.scratch.code;
  win.resize(vertexCount);
  fixed.resize(vertexCount);
  codes.resize(vertexCount);
  vertexStage(clip, vertexCount, f, win.data(), fixed.data(), codes.data());

  const bool fast = !wantColor && c.depthTest && c.depthWrite && c.item && !c.hits;
  const Shade shade = wantColor ? state.shade : Shade::None;
  if (state.depthFunc == DepthFunc::Greater)
    dispatch<true>(fast, shade, c, f, clip, indices, triangleCount, ids, colors, win.data(),
                   fixed.data(), codes.data());
  else
    dispatch<false>(fast, shade, c, f, clip, indices, triangleCount, ids, colors, win.data(),
                    fixed.data(), codes.data());
}

void drawLines(Target& target, const State& state, const glm::vec4* clip, size_t vertexCount,
               const uint32_t* indices, size_t lineCount, const glm::vec4& color, float depthBias) {
  const int W = target.width, H = target.height;
  if (W <= 0 || H <= 0) return;
  int sx0 = 0, sy0 = 0, sx1 = W, sy1 = H;  // pixel range [sx0, sx1) x [sy0, sy1)
  if (state.scissorTest) {
    sx0 = std::max(sx0, state.scissor.x);
    sy0 = std::max(sy0, state.scissor.y);
    sx1 = std::min(sx1, state.scissor.x + state.scissor.width);
    sy1 = std::min(sy1, state.scissor.y + state.scissor.height);
    if (sx0 >= sx1 || sy0 >= sy1) return;
  }
  const bool zeroToOne = state.clipDepth == ClipDepth::ZeroToOne;
  const bool less = state.depthFunc == DepthFunc::Less;
  const bool writeColor = !target.color.empty();
  const bool countHits = target.hits.size() == size_t(W) * H;
  // Signed distances to the near and far planes (inside >= 0).
  auto nearD = [&](const glm::dvec4& v) { return zeroToOne ? v.z : v.z + v.w; };
  auto farD = [](const glm::dvec4& v) { return v.w - v.z; };
  for (size_t s = 0; s < lineCount; ++s) {
    size_t i0 = 2 * s, i1 = 2 * s + 1;
    if (indices) {
      i0 = indices[2 * s];
      i1 = indices[2 * s + 1];
    }
    if (i0 >= vertexCount || i1 >= vertexCount)
      throw std::out_of_range("raster::drawLines: vertex index out of range");
    glm::dvec4 a(clip[i0]), b(clip[i1]);
    // Homogeneous clipping against near and far.
    bool visible = true;
    for (int plane = 0; plane < 2 && visible; ++plane) {
      const double da = plane == 0 ? nearD(a) : farD(a), db = plane == 0 ? nearD(b) : farD(b);
      if (da < 0 && db < 0) visible = false;
      else if (da < 0) a = a + (b - a) * (da / (da - db));
      else if (db < 0) b = b + (a - b) * (db / (db - da));
    }
    if (!visible || a.w <= 0 || b.w <= 0) continue;
    auto toWindow = [&](const glm::dvec4& v) {
      const glm::dvec3 n = glm::dvec3(v) / v.w;
      return glm::dvec3((n.x + 1) * 0.5 * W, (n.y + 1) * 0.5 * H, zeroToOne ? n.z : (n.z + 1) * 0.5);
    };
    glm::dvec3 p0 = toWindow(a), p1 = toWindow(b);
    // Liang-Barsky against the viewport rectangle.
    double t0 = 0, t1 = 1;
    const glm::dvec3 d = p1 - p0;
    const double pq[4][2] = {{-d.x, p0.x}, {d.x, W - p0.x}, {-d.y, p0.y}, {d.y, H - p0.y}};
    for (const auto& e : pq) {
      if (e[0] == 0) {
        if (e[1] < 0) visible = false;
      } else {
        const double r = e[1] / e[0];
        if (e[0] < 0) t0 = std::max(t0, r);
        else t1 = std::min(t1, r);
      }
    }
    if (!visible || t0 > t1) continue;
    const glm::dvec3 q0 = p0 + d * t0, q1 = p0 + d * t1;
    const bool xMajor = std::abs(d.x) >= std::abs(d.y);
    const int major = xMajor ? 0 : 1, minor = 1 - major;
    const double lo = std::min(q0[major], q1[major]), hi = std::max(q0[major], q1[major]);
    const double span = q1[major] - q0[major];
    if (span == 0) continue;
    const int first = int(std::ceil(lo - 0.5)), last = int(std::ceil(hi - 0.5)) - 1;
    for (int k = first; k <= last; ++k) {
      const double t = (k + 0.5 - q0[major]) / span;
      const int m = int(std::floor(q0[minor] + t * (q1[minor] - q0[minor])));
      const int x = xMajor ? k : m, y = xMajor ? m : k;
      if (x < sx0 || x >= sx1 || y < sy0 || y >= sy1) continue;
      float z = float(q0.z + t * (q1.z - q0.z));
      z = std::clamp(less ? z - depthBias : z + depthBias, 0.0f, 1.0f);
      const size_t p = target.index(x, y);
      if (state.depthTest) {
        if (less ? !(z < target.depth[p]) : !(z > target.depth[p])) continue;
        if (state.depthWrite) target.depth[p] = z;
      }
      if (writeColor) target.color[p] = color;
      if (countHits) ++target.hits[p];
    }
  }
}

}  // namespace raster
