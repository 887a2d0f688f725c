// Internals shared by the raster core's files (display/raster_*.cpp), not part of its interface:
// fixed point, the NDC -> window frame, snapped vertices and the per-draw context.
//
// The pipeline, one file per stage:
//   raster.cpp                  drawTriangles: checks, per-draw setup, the triangle loop
//   raster_vertex.cpp           transform, outcodes and window coordinates of every vertex
//   raster_clip.cpp             homogeneous clipping of the triangles that need it, fan
//   raster_triangle.cpp         edge-function rasterisation of one snapped triangle
//   raster_small_triangles.cpp  the item+depth path's SSE2 setup for small triangles
//   raster_target.cpp           the render target's buffers
//   raster_lines.cpp            drawLines
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "display/raster/raster.h"

#if defined(__SSE2__) && !defined(RASTER_NO_SIMD)
#include <emmintrin.h>
#define RASTER_SSE2 1
#else
#define RASTER_SSE2 0
#endif

// The named steps of the hot kernels: always inlined, so that naming them costs no speed.
#define RASTER_INLINE inline __attribute__((always_inline))

namespace raster::detail {

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

/// Window coordinate -> fixed point, rounded to nearest even like cvtps2dq in the vertex
/// stage (|x| <= kGuardPixels + small, so the result fits easily).
inline int32_t toFixed(float x) {
#if RASTER_SSE2
  return _mm_cvtss_si32(_mm_set_ss(x * float(kOne)));
#else
  return static_cast<int32_t>(std::lrint(x * float(kOne)));
#endif
}

// A vertex ready for triangle setup.
struct SVert {
  int32_t X, Y;            // snapped window position
  float x, y, z, q;        // exact window position, depth, 1/w
  const glm::vec4* color;  // per-vertex colour (smooth shading only)
};

/// A vertex made by clipping: snapped here.
inline SVert makeSVert(const glm::vec4& win, const glm::vec4* color) {
  return SVert{toFixed(win.x), toFixed(win.y), win.x, win.y, win.z, win.w, color};
}
/// An original vertex: snapped by the vertex stage.
inline SVert makeSVert(const glm::vec4& win, const glm::ivec2& fixed, const glm::vec4* color) {
  return SVert{fixed.x, fixed.y, win.x, win.y, win.z, win.w, color};
}

/// Twice the signed area in fixed point (> 0: counter-clockwise in the y-up window).
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

// The vertex stage's output and the draw's vertex arrays, indexed by vertex.
struct Vertices {
  const glm::vec4* clip;    // clip-space positions
  const glm::vec4* win;     // window coordinates (x_w, y_w, depth, 1/w)
  const glm::ivec2* fixed;  // snapped window positions
  const uint16_t* codes;    // outcodes
  const glm::vec4* colors;  // per-vertex colours, or null
};

// The triangles of a draw call.
struct Triangles {
  const uint32_t* indices;  // 3 per triangle, or null: non-indexed
  size_t count;
  const uint32_t* ids;      // item ids, or null: the triangle index
};

// An inclusive pixel range [x0, x1] x [y0, y1].
struct PixelRange {
  int x0, y0, x1, y1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};

/// The pixels a draw may write: the whole target (width, height >= 1), clamped to the state's
/// scissor rectangle if its test is on.
PixelRange drawableRange(const Target& target, const State& state);

// Calls M(Fast, S, Greater) for every instantiation of the pipeline's templates: the item+depth
// path (Fast: no colour, depth test and write on, an item buffer, no hits hook) and the generic
// path with each shading, each for the depth test LESS and GREATER.
#define RASTER_FOR_EACH_PIPELINE(M)                                                           \
  M(true, Shade::None, false) M(true, Shade::None, true) M(false, Shade::None, false)         \
  M(false, Shade::None, true) M(false, Shade::Flat, false) M(false, Shade::Flat, true)        \
  M(false, Shade::Smooth, false) M(false, Shade::Smooth, true)

/// The vertex indices of triangle t (non-indexed drawing: 3t, 3t+1, 3t+2).
inline void triangleVertices(const uint32_t* indices, size_t t, uint32_t (&vi)[3]) {
  for (int k = 0; k < 3; ++k) vi[k] = indices ? indices[3 * t + k] : uint32_t(3 * t + k);
}

/// Calls draw(vi, id, clipped) for each triangle of t, in order, that is not entirely outside
/// one plane: its vertex indices, its item id, and whether it crosses a clipping plane.
template <class Draw>
RASTER_INLINE void forEachTriangle(const Vertices& v, const Triangles& t, const Draw& draw) {
  const Triangles tris = t;  // a copy, which the calls below cannot be assumed to change
  const uint16_t* const codes = v.codes;
  for (size_t k = 0; k < tris.count; ++k) {
    uint32_t vi[3];
    triangleVertices(tris.indices, k, vi);
    const uint32_t o0 = codes[vi[0]], o1 = codes[vi[1]], o2 = codes[vi[2]];
    if (o0 & o1 & o2) continue;  // entirely outside one plane
    draw(vi, tris.ids ? tris.ids[k] : uint32_t(k), ((o0 | o1 | o2) & kClipBits) != 0);
  }
}

}  // namespace raster::detail
