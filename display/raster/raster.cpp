// The raster core's draw call: checks, per-draw setup and the triangle loop. One pipeline
// (outcodes -> homogeneous clipping -> snapping -> edge-function rasterisation), instantiated
// for the item+depth fast path and for the generic path.
#include "display/raster/raster.h"

#include <algorithm>
#include <stdexcept>

#include "display/raster/raster_clip.h"
#include "display/raster/raster_internal.h"
#include "display/raster/raster_small_triangles.h"
#include "display/raster/raster_triangle.h"
#include "display/raster/raster_vertex.h"

namespace raster {
namespace detail {

PixelRange drawableRange(const Target& target, const State& state) {
  PixelRange r{0, 0, target.width - 1, target.height - 1};
  if (!state.scissorTest) return r;
  r.x0 = std::max(r.x0, state.scissor.x);
  r.y0 = std::max(r.y0, state.scissor.y);
  r.x1 = int(std::min<int64_t>(r.x1, int64_t(state.scissor.x) + state.scissor.width - 1));
  r.y1 = int(std::min<int64_t>(r.y1, int64_t(state.scissor.y) + state.scissor.height - 1));
  return r;
}

}  // namespace detail

namespace {

using namespace detail;

#if RASTER_SSE2
/// Whether some of idx[i..) is above `last`, for the indices up to the last multiple of 4;
/// advances i past them. Unsigned compares through signed ones of values offset by 2^31;
/// four independent accumulators of "some index > last".
bool someIndexAbove(const uint32_t* idx, size_t n, uint32_t last, size_t& i) {
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
  return _mm_movemask_epi8(_mm_or_si128(_mm_or_si128(bad0, bad1), _mm_or_si128(bad2, bad3)));
}
#endif

/// Whether all n indices are below `limit` (vertexCount, >= 1).
bool indicesBelow(const uint32_t* idx, size_t n, size_t limit) {
  if (limit > 0xFFFFFFFFu) return true;
  const uint32_t last = uint32_t(limit - 1);  // largest valid index
  size_t i = 0;
#if RASTER_SSE2
  if (someIndexAbove(idx, n, last, i)) return false;
#endif
  uint32_t m = 0;
  for (; i < n; ++i) m = std::max(m, idx[i]);
  return m <= last;
}

/// Whether an optional buffer is absent (empty) or has one value per pixel.
template <class Buffer>
bool absentOrSized(const Buffer& buffer, size_t pixels) {
  return buffer.empty() || buffer.size() == pixels;
}

/// Throws std::invalid_argument unless every buffer of the target has one value per pixel.
void checkBuffers(const Target& target) {
  const size_t pixels = size_t(target.width) * size_t(target.height);
  if (target.depth.size() != pixels || !absentOrSized(target.item, pixels) ||
      !absentOrSized(target.color, pixels) || !absentOrSized(target.hits, pixels))
    throw std::invalid_argument("raster::drawTriangles: target buffers do not match its size");
}

/// The draw's context: the target's buffers (colour iff wantColor), pixels r, state.
Ctx makeCtx(Target& target, const State& state, const PixelRange& r, bool wantColor) {
  Ctx c{};
  c.x0 = r.x0, c.y0 = r.y0, c.x1 = r.x1, c.y1 = r.y1;
  c.depth = target.depth.data();
  c.item = target.item.empty() ? nullptr : target.item.data();
  c.color = wantColor ? target.color.data() : nullptr;
  c.hits = target.hits.empty() ? nullptr : target.hits.data();
  c.width = target.width;
  c.cullBack = state.cull == Cull::Back;
  c.depthTest = state.depthTest;
  c.depthWrite = state.depthWrite;
  return c;
}

/// The NDC -> window mapping of the target, in the state's depth convention.
Frame makeFrame(const Target& target, const State& state) {
  Frame f;
  f.halfW = 0.5f * float(target.width);
  f.halfH = 0.5f * float(target.height);
  f.gx = kGuardPixels / f.halfW - 1.0f;
  f.gy = kGuardPixels / f.halfH - 1.0f;
  const bool zeroToOne = state.clipDepth == ClipDepth::ZeroToOne;
  f.nearW = zeroToOne ? 0.0f : 1.0f;
  f.zScale = zeroToOne ? 1.0f : 0.5f;
  f.zBias = zeroToOne ? 0.0f : 0.5f;
  return f;
}

/// Vertex stage: outcodes and window coordinates of every vertex, once per draw, in the
/// target's scratch arrays.
Vertices runVertexStage(Target::Scratch& s, const glm::vec4* clip, size_t vertexCount,
                        const Frame& f, const glm::vec4* colors) {
  s.window.resize(vertexCount);
  s.fixed.resize(vertexCount);
  s.code.resize(vertexCount);
  vertexStage(clip, vertexCount, f, s.window.data(), s.fixed.data(), s.code.data());
  return Vertices{clip, s.window.data(), s.fixed.data(), s.code.data(), colors};
}

/// The triangle loop: trivial reject, unclipped triangles straight to the rasteriser, or
/// clipping.
template <bool Fast, Shade S, bool Greater>
void drawAll(Ctx& c, const Frame& f, const Vertices& v, const Triangles& t) {
  const Vertices verts = v;  // a copy, which the calls below cannot be assumed to change
  forEachTriangle(v, t, [&](const uint32_t (&vi)[3], uint32_t id, bool clipped) {
    c.id = id;
    if constexpr (S == Shade::Flat) c.flat = verts.colors[vi[2]];  // provoking vertex: the last
    if (clipped) return clipAndDraw<Fast, S, Greater>(c, f, v, vi);
    auto snapped = [&](uint32_t i) {
      return makeSVert(verts.win[i], verts.fixed[i],
                       S == Shade::Smooth ? verts.colors + i : nullptr);
    };
    drawSnapped<Fast, S, Greater>(c, snapped(vi[0]), snapped(vi[1]), snapped(vi[2]));
  });
}

/// Picks the instantiation of the pipeline for the path, the shading and the depth function.
template <bool Greater>
void dispatch(bool fast, Shade shade, Ctx& c, const Frame& f, const Vertices& v,
              const Triangles& t) {
  if (fast)
#if RASTER_SSE2
    drawAllFast<Greater>(c, f, v, t);
#else
    drawAll<true, Shade::None, Greater>(c, f, v, t);
#endif
  else if (shade == Shade::None)
    drawAll<false, Shade::None, Greater>(c, f, v, t);
  else if (shade == Shade::Flat)
    drawAll<false, Shade::Flat, Greater>(c, f, v, t);
  else
    drawAll<false, Shade::Smooth, Greater>(c, f, v, t);
}

/// The number of triangles to draw: all of them once their indices are checked against
/// vertexCount, or the whole triangles of an unindexed list.
size_t checkedTriangleCount(const uint32_t* indices, size_t triangleCount, size_t vertexCount) {
  if (!indices) return std::min(triangleCount, vertexCount / 3);
  if (!indicesBelow(indices, 3 * triangleCount, vertexCount))
    throw std::out_of_range("raster::drawTriangles: vertex index out of range");
  return triangleCount;
}

}  // namespace

void drawTriangles(Target& target, const State& state, const glm::vec4* clip, size_t vertexCount,
                   const uint32_t* indices, size_t triangleCount, const uint32_t* ids,
                   const glm::vec4* colors) {
  if (triangleCount == 0 || vertexCount == 0 || target.width < 1 || target.height < 1) return;
  checkBuffers(target);
  triangleCount = checkedTriangleCount(indices, triangleCount, vertexCount);
  const PixelRange r = drawableRange(target, state);
  if (r.empty()) return;
  const bool wantColor = state.shade != Shade::None && colors && !target.color.empty();
  Ctx c = makeCtx(target, state, r, wantColor);
  const Frame f = makeFrame(target, state);
  const Vertices v = runVertexStage(target.scratch, clip, vertexCount, f, colors);
  const Triangles t{indices, triangleCount, ids};
  const bool fast = !wantColor && c.depthTest && c.depthWrite && c.item && !c.hits;
  const Shade shade = wantColor ? state.shade : Shade::None;
  if (state.depthFunc == DepthFunc::Greater)
    dispatch<true>(fast, shade, c, f, v, t);
  else
    dispatch<false>(fast, shade, c, f, v, t);
}

}  // namespace raster
