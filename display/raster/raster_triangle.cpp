// Rasterisation of one snapped triangle. Each row of the bounding box is walked in chunks of 4
// pixels, stepping the 64-bit edge functions incrementally: the sign bits of E0|E1|E2 give the
// chunk's coverage mask (exact integer test). The item+depth fast path blends every chunk of
// the row with SSE2, whatever its mask: with the small triangles of item buffers, branching on
// coverage costs more in mispredictions than the few extra blends. The generic path skips
// empty chunks and stops after the row's span (a convex triangle covers a single span per
// row), then shades the covered pixels one by one. Without SSE2 the same masks are computed
// with scalar code (bit-identical results).
#include "display/raster/raster_triangle.h"

#include <cstddef>

#include "display/raster/raster_interpolation.h"
#include "display/raster/raster_item_depth.h"

namespace raster::detail {
namespace {

/// Branch-free min (GCC tends to emit unpredictable branches for std::min here); |a - b| < 2^63.
inline int64_t min64(int64_t a, int64_t b) {
  const int64_t d = b - a;
  return a + (d & (d >> 63));
}
/// Branch-free max, as min64.
inline int64_t max64(int64_t a, int64_t b) {
  const int64_t d = b - a;
  return b - (d & (d >> 63));
}

// Pixels [ix0, ix1] x [iy0, iy1] (empty if ix0 > ix1 or iy0 > iy1).
struct PixelBox {
  int ix0, ix1, iy0, iy1;
};

/// Pixels whose centres lie in the snapped bounding box, clamped to viewport and scissor.
RASTER_INLINE PixelBox pixelBox(const Ctx& c, const SVert& v0, const SVert& v1, const SVert& v2) {
  const int64_t minX = min64(v0.X, min64(v1.X, v2.X)), maxX = max64(v0.X, max64(v1.X, v2.X));
  const int64_t minY = min64(v0.Y, min64(v1.Y, v2.Y)), maxY = max64(v0.Y, max64(v1.Y, v2.Y));
  return PixelBox{int(max64(c.x0, (minX - kHalf + kOne - 1) >> kSubpixelBits)),
                  int(min64(c.x1, (maxX - kHalf) >> kSubpixelBits)),
                  int(max64(c.y0, (minY - kHalf + kOne - 1) >> kSubpixelBits)),
                  int(min64(c.y1, (maxY - kHalf) >> kSubpixelBits))};
}

// Edge functions at the centre of pixel (ix0, iy0), E = A*(px-Xa) + B*(py-Ya), > 0 inside, and
// their steps per column (sx) and row (sy).
struct Edges {
  int64_t sx[3], sy[3], e0[3];
};

/// The Edges of triangle (v0, v1, v2) from pixel (ix0, iy0). Edge k is opposite vertex k.
/// Biased by -1 unless top-left, so "inside" is simply E >= 0, i.e. the sign bit of
/// (E0 | E1 | E2) is clear.
RASTER_INLINE Edges edgeFunctions(const SVert& v0, const SVert& v1, const SVert& v2, int ix0,
                                  int iy0) {
  const int64_t px = int64_t(ix0) * kOne + kHalf, py = int64_t(iy0) * kOne + kHalf;
  const SVert* ea[3] = {&v1, &v2, &v0};
  const SVert* eb[3] = {&v2, &v0, &v1};
  Edges e;
  for (int k = 0; k < 3; ++k) {
    const int64_t A = int64_t(ea[k]->Y) - eb[k]->Y, B = int64_t(eb[k]->X) - ea[k]->X;
    const int64_t topLeft = (A > 0) | ((A == 0) & (B < 0));
    e.sx[k] = A * kOne;
    e.sy[k] = B * kOne;
    e.e0[k] = A * (px - ea[k]->X) + B * (py - ea[k]->Y) - (1 - topLeft);
  }
  return e;
}

/// The lanes of the 4-pixel chunk starting at column i that lie up to ix1, as a 4-bit mask.
RASTER_INLINE int validLanes(int i, int ix1) { return 0xF >> int(max64(0, i + 3 - ix1)); }

/// Calls f(l) for each lane l set in the 4-bit `mask`, in increasing order.
template <class F>
RASTER_INLINE void forEachLane(int mask, const F& f) {
  for (int m = mask; m; m &= m - 1) f(__builtin_ctz(unsigned(m)));
}

// The fragment stage of one triangle: depth test, then the writes. It holds its own copies of
// the context's pointers, so that stores to the buffers cannot be assumed to alias the context.
template <bool Fast, Shade S, bool Greater>
struct Fragments {
  float* depth;
  uint32_t* item;
  glm::vec4* color;
  uint32_t* hits;
  uint32_t id;
  bool depthTest, depthWrite;
  glm::vec4 flat;
  Gouraud gouraud;  // smooth shading only

  explicit Fragments(const Ctx& c)
      : depth(c.depth), item(c.item), color(c.color), hits(c.hits), id(c.id),
        depthTest(c.depthTest), depthWrite(c.depthWrite), flat(c.flat) {}

  /// Depth test: LESS, or GREATER for reversed depth.
  static bool passes(float z, float stored) { return Greater ? stored < z : z < stored; }

  /// One fragment at offset fk = i - ix0 of row offset dj, buffer index idx, depth z.
  RASTER_INLINE void operator()(size_t idx, float z, float fk, double dj) const {
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
      if constexpr (S == Shade::Flat) color[idx] = flat;
      if constexpr (S == Shade::Smooth) color[idx] = gouraud.at(fk, dj);
      if (hits) ++hits[idx];
    }
  }
};

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

// A step of the three edges' values (the same in every lane).
struct EdgeSteps {
  __m128i s0, s1, s2;
  EdgeSteps(int64_t a, int64_t b, int64_t c)
      : s0(_mm_set1_epi64x(a)), s1(_mm_set1_epi64x(b)), s2(_mm_set1_epi64x(c)) {}
};

// Edge k's values at lanes 0,1 (lo) and 2,3 (hi) of a chunk of 4 pixels. (Spelled out per
// edge so that they stay in registers even at -O2.)
struct EdgeLanes {
  __m128i e0Lo, e1Lo, e2Lo, e0Hi, e1Hi, e2Hi;

  /// The chunk of columns ix0..ix0+3 of row iy0.
  static RASTER_INLINE EdgeLanes first(const Edges& e) {
    auto lo = [&](int k) { return _mm_set_epi64x(e.e0[k] + e.sx[k], e.e0[k]); };
    auto hi = [&](int k) { return _mm_set_epi64x(e.e0[k] + 3 * e.sx[k], e.e0[k] + 2 * e.sx[k]); };
    return EdgeLanes{lo(0), lo(1), lo(2), hi(0), hi(1), hi(2)};
  }
  /// Adds a step to every lane.
  RASTER_INLINE void step(const EdgeSteps& s) {
    e0Lo = _mm_add_epi64(e0Lo, s.s0), e1Lo = _mm_add_epi64(e1Lo, s.s1);
    e2Lo = _mm_add_epi64(e2Lo, s.s2);
    e0Hi = _mm_add_epi64(e0Hi, s.s0), e1Hi = _mm_add_epi64(e1Hi, s.s1);
    e2Hi = _mm_add_epi64(e2Hi, s.s2);
  }
  /// The outside lanes as a 4-bit mask: the sign bits of E0|E1|E2.
  RASTER_INLINE int outside() const {
    const __m128i oLo = _mm_or_si128(_mm_or_si128(e0Lo, e1Lo), e2Lo);
    const __m128i oHi = _mm_or_si128(_mm_or_si128(e0Hi, e1Hi), e2Hi);
    return _mm_movemask_pd(_mm_castsi128_pd(oLo)) | _mm_movemask_pd(_mm_castsi128_pd(oHi)) << 2;
  }
};

/// Walks the rows of box b in chunks of 4 pixels with SSE2 edge functions (2 per register):
/// the item+depth path blends whole chunks, the generic path shades the covered pixels.
template <bool Fast, Shade S, bool Greater>
RASTER_INLINE void walkRows(const Fragments<Fast, S, Greater>& frag, int width, const PixelBox& b,
                            const Edges& e, const DepthPlane& dp) {
  EdgeLanes row = EdgeLanes::first(e);
  const EdgeSteps down(e.sy[0], e.sy[1], e.sy[2]), right(4 * e.sx[0], 4 * e.sx[1], 4 * e.sx[2]);
  const __m128 dz4 = _mm_set1_ps(float(dp.dzdx)), four4 = _mm_set1_ps(4.0f);
  const __m128 lanes4 = _mm_set_ps(3.0f, 2.0f, 1.0f, 0.0f);
  const __m128i idv = _mm_set1_epi32(int(frag.id));
  size_t rowBase = size_t(b.iy0) * size_t(width) + size_t(b.ix0);
  for (int j = b.iy0; j <= b.iy1; ++j, rowBase += size_t(width)) {
    const double dj = j - b.iy0;
    const __m128 zr4 = _mm_set1_ps(depthRowStart(dp, dj));  // depth at pixel ix0 of this row
    bool seen = false;
    EdgeLanes chunk = row;
    row.step(down);
    __m128 fk4 = lanes4;
    for (int i = b.ix0; i <= b.ix1; i += 4) {
      const int mask = ~chunk.outside() & validLanes(i, b.ix1);
      chunk.step(right);
      const __m128 fk = fk4;
      fk4 = _mm_add_ps(fk4, four4);
      if (!Fast && !mask) {
        if (seen) break;
        continue;
      }
      seen = true;
      const __m128 z = clampDepth4(_mm_add_ps(zr4, rounded(_mm_mul_ps(dz4, fk))));
      const size_t k0 = rowBase + size_t(i - b.ix0);
      if constexpr (Fast) {
        if (i + 3 < width) {  // blend the 4 pixels at once
          const __m128 in = _mm_load_ps(reinterpret_cast<const float*>(kLaneMasks.m[mask]));
          blendItemDepth<Greater>(frag.depth + k0, frag.item + k0, z, in, idv);
          continue;
        }
      }
      alignas(16) float zs[4];
      _mm_store_ps(zs, z);
      forEachLane(mask, [&](int l) { frag(k0 + size_t(l), zs[l], float(i - b.ix0 + l), dj); });
    }
  }
}
#else
/// Coverage mask and clamped depths zs of the 4-pixel chunk at column offset k0 of a row
/// starting at depth zr; steps the edge values e along.
RASTER_INLINE int chunkCoverage(int64_t (&e)[3], const int64_t (&sx)[3], float zr, float dzdx,
                                int k0, float (&zs)[4]) {
  int mask = 0;
  for (int l = 0; l < 4; ++l) {
    mask |= int((e[0] | e[1] | e[2]) >= 0) << l;
    zs[l] = clampDepth(zr + rounded(dzdx * float(k0 + l)));
    e[0] += sx[0], e[1] += sx[1], e[2] += sx[2];
  }
  return mask;
}

/// Walks the rows of box b in chunks of 4 pixels and shades the covered pixels.
template <bool Fast, Shade S, bool Greater>
RASTER_INLINE void walkRows(const Fragments<Fast, S, Greater>& frag, int width, const PixelBox& b,
                            const Edges& e, const DepthPlane& dp) {
  const float fdzdx = float(dp.dzdx);
  int64_t row[3] = {e.e0[0], e.e0[1], e.e0[2]};
  size_t rowBase = size_t(b.iy0) * size_t(width) + size_t(b.ix0);
  for (int j = b.iy0; j <= b.iy1; ++j, rowBase += size_t(width)) {
    const double dj = j - b.iy0;
    const float zr = depthRowStart(dp, dj);  // depth at pixel ix0 of this row
    bool seen = false;
    int64_t ev[3] = {row[0], row[1], row[2]};
    row[0] += e.sy[0], row[1] += e.sy[1], row[2] += e.sy[2];
    for (int i = b.ix0; i <= b.ix1; i += 4) {
      float zs[4];
      const int mask = chunkCoverage(ev, e.sx, zr, fdzdx, i - b.ix0, zs) & validLanes(i, b.ix1);
      if (!mask) {
        if (seen) break;
        continue;
      }
      seen = true;
      const size_t k0 = rowBase + size_t(i - b.ix0);
      forEachLane(mask, [&](int l) { frag(k0 + size_t(l), zs[l], float(i - b.ix0 + l), dj); });
    }
  }
}
#endif

}  // namespace

template <bool Fast, Shade S, bool Greater>
void rasterTriangle(const Ctx& c, const SVert& v0, const SVert& v1, const SVert& v2, int64_t area) {
  const PixelBox b = pixelBox(c, v0, v1, v2);
  if (b.ix0 > b.ix1 || b.iy0 > b.iy1) return;
  const Edges e = edgeFunctions(v0, v1, v2, b.ix0, b.iy0);
  // Attribute planes from the exact (unsnapped) positions; snapped ones if those degenerate.
  const Plane pl = makePlane(v0, v1, v2, area);
  const DepthPlane dp = depthAt(pl, v0, v1, v2, b.ix0, b.iy0);
  Fragments<Fast, S, Greater> frag(c);
  if constexpr (S == Shade::Smooth) frag.gouraud = Gouraud(pl, v0, v1, v2, b.ix0, b.iy0);
  walkRows(frag, c.width, b, e, dp);
}

#define RASTER_INSTANTIATE(Fast, S, Greater)                                                 \
  template void rasterTriangle<Fast, S, Greater>(const Ctx&, const SVert&, const SVert&,     \
                                                 const SVert&, int64_t);
RASTER_FOR_EACH_PIPELINE(RASTER_INSTANTIATE)
#undef RASTER_INSTANTIATE

}  // namespace raster::detail
