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
#include "display/raster/raster_small_triangles.h"

#if RASTER_SSE2
#include <cstddef>
#include <type_traits>

#include "display/raster/raster_clip.h"
#include "display/raster/raster_interpolation.h"
#include "display/raster/raster_item_depth.h"
#include "display/raster/raster_triangle.h"

namespace raster::detail {
namespace {

constexpr int kSmallRows = 4;
constexpr int32_t kSmallSpan = 1 << 14;

/// SSE2 min of 32-bit lanes (pminsd is SSE4.1).
RASTER_INLINE __m128i minEpi32(__m128i a, __m128i b) {
  const __m128i gt = _mm_cmpgt_epi32(a, b);
  return _mm_or_si128(_mm_and_si128(gt, b), _mm_andnot_si128(gt, a));
}
/// SSE2 max of 32-bit lanes (pmaxsd is SSE4.1).
RASTER_INLINE __m128i maxEpi32(__m128i a, __m128i b) {
  const __m128i gt = _mm_cmpgt_epi32(a, b);
  return _mm_or_si128(_mm_and_si128(gt, a), _mm_andnot_si128(gt, b));
}

/// Lane 0 and lane 1 of a: (x, y).
RASTER_INLINE int lane0(__m128i a) { return _mm_cvtsi128_si32(a); }
RASTER_INLINE int lane1(__m128i a) { return _mm_cvtsi128_si32(_mm_shuffle_epi32(a, 0x55)); }

// Per-draw constants of fastTriangle.
struct FastCtx {
  __m128i clipLo, clipHi;  // (x0, y0, 0, 0), (x1, y1, 0, 0): pixel range of viewport & scissor
  int width;
};

// A triangle's snapped bounding box [mn, mx] and the pixels whose centres lie in it, [lo, hi]
// (as in rasterTriangle), dims = hi - lo; lanes x, y.
struct FastBox {
  __m128i mn, mx, lo, hi, dims;
};

/// The FastBox of snapped corners p0, p1, p2 (X, Y, 0, 0); false if it holds no pixel centre.
RASTER_INLINE bool fastBox(const FastCtx& fc, __m128i p0, __m128i p1, __m128i p2, FastBox& b) {
  b.mn = minEpi32(p0, minEpi32(p1, p2));
  b.mx = maxEpi32(p0, maxEpi32(p1, p2));
  const __m128i first = _mm_add_epi32(b.mn, _mm_set1_epi32(kOne - 1 - kHalf));
  b.lo = maxEpi32(_mm_srai_epi32(first, kSubpixelBits), fc.clipLo);
  b.hi = minEpi32(_mm_srai_epi32(_mm_sub_epi32(b.mx, _mm_set1_epi32(kHalf)), kSubpixelBits),
                  fc.clipHi);
  if (_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(b.lo, b.hi))) & 3) return false;
  b.dims = _mm_sub_epi32(b.hi, b.lo);  // columns - 1, rows - 1
  return true;
}

/// Whether both spans of the box are below kSmallSpan.
RASTER_INLINE bool smallSpans(const FastBox& b) {
  const __m128i spanOk = _mm_cmplt_epi32(_mm_sub_epi32(b.mx, b.mn), _mm_set1_epi32(kSmallSpan));
  return (_mm_movemask_ps(_mm_castsi128_ps(spanOk)) & 3) == 3;
}

/// Twice the signed area of snapped triangle (i0, i1, i2), exact in 64 bits.
RASTER_INLINE int64_t signedArea2(const glm::ivec2* fixed, uint32_t i0, uint32_t i1, uint32_t i2) {
  const int64_t X0 = fixed[i0].x, Y0 = fixed[i0].y;
  const int64_t X1 = fixed[i1].x - X0, Y1 = fixed[i1].y - Y0;
  const int64_t X2 = fixed[i2].x - X0, Y2 = fixed[i2].y - Y0;
  return X1 * Y2 - X2 * Y1;
}

// The three edges' values in 32-bit lanes.
struct Edge3 {
  __m128i e0, e1, e2;
  /// Adds a step to every lane.
  RASTER_INLINE void add(const Edge3& s) {
    e0 = _mm_add_epi32(e0, s.e0), e1 = _mm_add_epi32(e1, s.e1), e2 = _mm_add_epi32(e2, s.e2);
  }
  /// All ones in the lanes outside the triangle: the sign of E0|E1|E2.
  RASTER_INLINE __m128i outside() const {
    return _mm_srai_epi32(_mm_or_si128(_mm_or_si128(e0, e1), e2), 31);
  }
};

// Edge functions of a small-span triangle: at the centres of pixels ix0..ix0+3 of row iy0
// (lane l: column ix0 + l), and their steps per row and per column.
struct SmallEdges {
  Edge3 at, down, right;
};

// Edge k's coefficients (A, B) (pair k of ab) and the offsets (px - Xa, py - Ya) of the first
// pixel centre from its first vertex (pair k of o), 16-bit.
struct EdgeCoefficients {
  __m128i ab, o;
};

/// EdgeCoefficients of triangle (p0, p1, p2), pixel lo = (ix0, iy0), relative to v0: r1 = v1 -
/// v0, r2 = v2 - v0, rc = centre of (ix0, iy0) - v0. Edge k (opposite vertex k) runs from a =
/// (1, 2, 0)[k] to b = (2, 0, 1)[k] of the triangle as given; pair k of the vectors below
/// belongs to edge k (pair 3 is zero). For a clockwise triangle (flip), (A, B) and so E change
/// sign: the edges of (v0, v2, v1), exactly.
RASTER_INLINE EdgeCoefficients edgeCoefficients(__m128i p0, __m128i p1, __m128i p2, __m128i lo,
                                                bool flip) {
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
  return EdgeCoefficients{ab, _mm_sub_epi16(rc, ra)};  // o = (px - Xa, py - Ya)
}

/// Lane l: the edge function of the edge whose pair shuffle selector is `sel`, at column
/// ix0 + l of row iy0.
template <int sel>
RASTER_INLINE __m128i edgeLanes(const EdgeCoefficients& k, __m128i bias) {
  const __m128i colOffset = _mm_setr_epi16(0, 0, kOne, 0, 2 * kOne, 0, 3 * kOne, 0);
  return _mm_add_epi32(_mm_madd_epi16(_mm_shuffle_epi32(k.ab, sel),
                                      _mm_add_epi16(_mm_shuffle_epi32(k.o, sel), colOffset)),
                       _mm_shuffle_epi32(bias, sel));
}

/// The SmallEdges of triangle (p0, p1, p2) from pixel lo (see edgeCoefficients), with pmaddwd.
RASTER_INLINE SmallEdges smallEdges(__m128i p0, __m128i p1, __m128i p2, __m128i lo, bool flip) {
  const EdgeCoefficients k = edgeCoefficients(p0, p1, p2, lo, flip);
  const __m128i sx = _mm_madd_epi16(k.ab, _mm_setr_epi16(kOne, 0, kOne, 0, kOne, 0, kOne, 0));
  const __m128i sy = _mm_madd_epi16(k.ab, _mm_setr_epi16(0, kOne, 0, kOne, 0, kOne, 0, kOne));
  // Bias -1 unless top-left (A > 0, or A == 0 and B < 0), so that "inside" is E >= 0.
  const __m128i zero = _mm_setzero_si128();
  const __m128i topLeft = _mm_or_si128(
      _mm_cmpgt_epi32(sx, zero), _mm_and_si128(_mm_cmpeq_epi32(sx, zero), _mm_cmpgt_epi32(zero, sy)));
  const __m128i bias = _mm_andnot_si128(topLeft, _mm_set1_epi32(-1));
  return SmallEdges{
      {edgeLanes<0x00>(k, bias), edgeLanes<0x55>(k, bias), edgeLanes<0xAA>(k, bias)},
      {_mm_shuffle_epi32(sy, 0x00), _mm_shuffle_epi32(sy, 0x55), _mm_shuffle_epi32(sy, 0xAA)},
      {_mm_shuffle_epi32(sx, 0x00), _mm_shuffle_epi32(sx, 0x55), _mm_shuffle_epi32(sx, 0xAA)}};
}

/// The depth plane of counter-clockwise triangle (i0, j1, j2) from pixel (ix0, iy0), as
/// rasterTriangle computes it.
RASTER_INLINE DepthPlane depthPlane(const glm::vec4* win, const glm::ivec2* fixed, uint32_t i0,
                                    uint32_t j1, uint32_t j2, int64_t area, int ix0, int iy0) {
  const SVert v0 = makeSVert(win[i0], fixed[i0], nullptr);
  const SVert v1 = makeSVert(win[j1], fixed[j1], nullptr);
  const SVert v2 = makeSVert(win[j2], fixed[j2], nullptr);
  return depthAt(makePlane(v0, v1, v2, area), v0, v1, v2, ix0, iy0);
}

// Where a triangle's box starts in the depth and item buffers, their row length and the id.
struct BoxTarget {
  float* depth;
  uint32_t* item;
  size_t width;
  __m128i id;
  /// Depth test and write of the 4 pixels at offset off from the box's first pixel (lanes of
  /// `in` all ones or all zeros).
  template <bool Greater>
  RASTER_INLINE void blend(size_t off, __m128 z, __m128i in) const {
    blendItemDepth<Greater>(depth + off, item + off, z, _mm_castsi128_ps(in), id);
  }
};

/// A box of at most 4 x kSmallRows pixel centres, one chunk per row: the coverage `in` of
/// every row, branch-free (lanes beyond the box masked); false if no centre is covered.
RASTER_INLINE bool smallBoxCoverage(Edge3 e, const Edge3& down, __m128i dims,
                                    __m128i (&in)[kSmallRows]) {
  const __m128i colValid = _mm_cmpgt_epi32(_mm_shuffle_epi32(dims, 0x00), _mm_setr_epi32(-1, 0, 1, 2));
  const __m128i rowsM1v = _mm_shuffle_epi32(dims, 0x55);
  __m128i any = _mm_setzero_si128();
  for (int r = 0; r < kSmallRows; ++r) {
    const __m128i valid = _mm_and_si128(colValid, _mm_cmpgt_epi32(rowsM1v, _mm_set1_epi32(r - 1)));
    in[r] = _mm_andnot_si128(e.outside(), valid);
    any = _mm_or_si128(any, in[r]);
    e.add(down);
  }
  return _mm_movemask_epi8(any) != 0;
}

/// Blends rows 0..rowsM1 of a small box with coverage `in` and depth plane dp. Row r starts
/// at depthRowStart(dp, r) (cvtpd2ps rounds like float(double)), its pixel l at
/// clamp(start + float(dzdx)*l).
template <bool Greater>
RASTER_INLINE void blendSmallBox(const BoxTarget& t, const DepthPlane& dp, int rowsM1,
                                 const __m128i (&in)[kSmallRows]) {
  const __m128d zz = _mm_set1_pd(dp.z00), dy = _mm_set1_pd(dp.dzdy);
  const __m128 zr = _mm_movelh_ps(
      _mm_cvtpd_ps(_mm_add_pd(zz, rounded(_mm_mul_pd(dy, _mm_set_pd(1.0, 0.0))))),
      _mm_cvtpd_ps(_mm_add_pd(zz, rounded(_mm_mul_pd(dy, _mm_set_pd(3.0, 2.0))))));
  const __m128 lanes4 = _mm_set_ps(3.0f, 2.0f, 1.0f, 0.0f);
  const __m128 dz = rounded(_mm_mul_ps(_mm_set1_ps(float(dp.dzdx)), lanes4));
  auto rowZ = [&](__m128 start) { return clampDepth4(_mm_add_ps(start, dz)); };
  const size_t w = t.width;
  t.blend<Greater>(0, rowZ(_mm_shuffle_ps(zr, zr, 0x00)), in[0]);
  if (rowsM1 > 0) t.blend<Greater>(w, rowZ(_mm_shuffle_ps(zr, zr, 0x55)), in[1]);
  if (rowsM1 > 1) t.blend<Greater>(2 * w, rowZ(_mm_shuffle_ps(zr, zr, 0xAA)), in[2]);
  if (rowsM1 > 2) t.blend<Greater>(3 * w, rowZ(_mm_shuffle_ps(zr, zr, 0xFF)), in[3]);
}

/// Blends a box of dims (columns - 1, rows - 1) in rows of up to 16 chunks of 4 pixels; every
/// chunk of the box is blended (masked), as in rasterTriangle.
template <bool Greater>
RASTER_INLINE void blendChunkedBox(const BoxTarget& t, const DepthPlane& dp, SmallEdges e,
                                   __m128i dims) {
  const __m128 dz4 = _mm_set1_ps(float(dp.dzdx)), four4 = _mm_set1_ps(4.0f);
  const __m128 lanes4 = _mm_set_ps(3.0f, 2.0f, 1.0f, 0.0f);
  const Edge3 right4{_mm_slli_epi32(e.right.e0, 2), _mm_slli_epi32(e.right.e1, 2),
                     _mm_slli_epi32(e.right.e2, 2)};
  const __m128i colsM1v = _mm_shuffle_epi32(dims, 0x00);
  const int chunks = (lane0(dims) >> 2) + 1, rowsM1 = lane1(dims);
  size_t rowOff = 0;
  for (int r = 0; r <= rowsM1; ++r, rowOff += t.width) {
    const __m128 zr4 = _mm_set1_ps(depthRowStart(dp, double(r)));
    Edge3 f = e.at;
    e.at.add(e.down);
    __m128 fk = lanes4;
    __m128i col = _mm_setr_epi32(-1, 0, 1, 2);  // column - 1 of each lane
    for (int k = 0; k < chunks; ++k) {
      const __m128i in = _mm_andnot_si128(f.outside(), _mm_cmpgt_epi32(colsM1v, col));
      t.blend<Greater>(rowOff + size_t(4 * k),
                       clampDepth4(_mm_add_ps(zr4, rounded(_mm_mul_ps(dz4, fk)))), in);
      f.add(right4);
      fk = _mm_add_ps(fk, four4);
      col = _mm_add_epi32(col, _mm_set1_epi32(4));
    }
  }
}

/// One unclipped triangle (vertex indices i0, i1, i2) of the item+depth path: bounding box,
/// orientation, then the small-box or chunked setup above, or rasterTriangle for large spans.
/// (Not inlined: the triangle loop stays small, and this measures a little faster.)
template <bool Greater>
__attribute__((noinline)) void fastTriangle(Ctx& c, const FastCtx& fc, const glm::vec4* win,
                                            const glm::ivec2* fixed, uint32_t i0, uint32_t i1,
                                            uint32_t i2, uint32_t id) {
  const __m128i p0 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(fixed + i0));  // X, Y, 0, 0
  const __m128i p1 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(fixed + i1));
  const __m128i p2 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(fixed + i2));
  FastBox b;
  if (!fastBox(fc, p0, p1, p2, b)) return;  // no centre
  const int64_t signedArea = signedArea2(fixed, i0, i1, i2);
  if (signedArea == 0 || (signedArea < 0 && c.cullBack)) return;
  const bool flip = signedArea < 0;  // clockwise: rasterise (v0, v2, v1)
  const int64_t area = flip ? -signedArea : signedArea;
  const uint32_t j1 = flip ? i2 : i1, j2 = flip ? i1 : i2;

  const int ix0 = lane0(b.lo), iy0 = lane1(b.lo), colsM1 = lane0(b.dims), rowsM1 = lane1(b.dims);
  if (!smallSpans(b) || ix0 + (colsM1 | 3) >= fc.width) {  // or the last chunk leaves the row
    c.id = id;
    rasterTriangle<true, Shade::None, Greater>(c, makeSVert(win[i0], fixed[i0], nullptr),
                                               makeSVert(win[j1], fixed[j1], nullptr),
                                               makeSVert(win[j2], fixed[j2], nullptr), area);
    return;
  }
  const SmallEdges e = smallEdges(p0, p1, p2, b.lo, flip);
  const size_t first = size_t(iy0) * size_t(c.width) + size_t(ix0);
  const BoxTarget t{c.depth + first, c.item + first, size_t(c.width), _mm_set1_epi32(int(id))};
  if (colsM1 < 4 && rowsM1 < kSmallRows) {
    // Coverage first; the depth plane only if some centre is covered.
    __m128i in[kSmallRows];
    if (!smallBoxCoverage(e.at, e.down, b.dims, in)) return;
    blendSmallBox<Greater>(t, depthPlane(win, fixed, i0, j1, j2, area, ix0, iy0), rowsM1, in);
    return;
  }
  blendChunkedBox<Greater>(t, depthPlane(win, fixed, i0, j1, j2, area, ix0, iy0), e, b.dims);
}

}  // namespace

template <bool Greater>
void drawAllFast(Ctx& c, const Frame& f, const Vertices& v, const Triangles& t) {
  FastCtx fc;
  fc.clipLo = _mm_setr_epi32(c.x0, c.y0, 0, 0);
  fc.clipHi = _mm_setr_epi32(c.x1, c.y1, 0, 0);
  fc.width = c.width;
  const glm::vec4* const win = v.win;  // copies, which the calls cannot be assumed to change
  const glm::ivec2* const fixed = v.fixed;
  forEachTriangle(v, t, [&](const uint32_t (&vi)[3], uint32_t id, bool clipped) {
    if (!clipped) return fastTriangle<Greater>(c, fc, win, fixed, vi[0], vi[1], vi[2], id);
    c.id = id;
    clipAndDraw<true, Shade::None, Greater>(c, f, v, vi);
  });
}

template void drawAllFast<false>(Ctx&, const Frame&, const Vertices&, const Triangles&);
template void drawAllFast<true>(Ctx&, const Frame&, const Vertices&, const Triangles&);

}  // namespace raster::detail
#endif
