// The raster core's vertex stage: transform, outcodes and window coordinates.
#include "display/raster/raster_vertex.h"

namespace raster {
namespace detail {
namespace {

/// Signed distance of v to clipping plane p (0 near, 1 far, 2-5 guard left/right/bottom/top);
/// inside iff >= 0. The clipper's planeDistD is the same in double.
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

/// Outcode of a clip-space vertex; NaN coordinates set bits (they end up clipped away).
inline uint32_t outcode(const glm::vec4& v, const Frame& f) {
  uint32_t c = uint32_t(!(v.x + v.w >= 0.0f)) | uint32_t(!(v.w - v.x >= 0.0f)) << 1 |
               uint32_t(!(v.y + v.w >= 0.0f)) << 2 | uint32_t(!(v.w - v.y >= 0.0f)) << 3;
  // w <= 0 with z inside [-w, w] is only the zero vector: flag it so it is never projected.
  c |= uint32_t(!(planeDist(v, 0, f) >= 0.0f) || !(v.w > 0.0f)) << kFirstPlaneBit;
  for (int p = 1; p < kPlaneCount; ++p)
    c |= uint32_t(!(planeDist(v, p, f) >= 0.0f)) << (kFirstPlaneBit + p);
  return c;
}

/// Clip space -> (x_w, y_w, depth, 1/w).
inline glm::vec4 project(const glm::vec4& v, const Frame& f) {
  const float q = 1.0f / v.w;
  return glm::vec4((rounded(v.x * q) + 1.0f) * f.halfW, (rounded(v.y * q) + 1.0f) * f.halfH,
                   rounded(v.z * q * f.zScale) + f.zBias, q);
}

/// Vertex v alone: outcode(), project() and toFixed().
inline void vertexStage1(const glm::vec4& clip, const Frame& f, glm::vec4& win, glm::ivec2& fixed,
                         uint16_t& code) {
  code = uint16_t(outcode(clip, f));
  win = project(clip, f);
  fixed = (code & kClipBits) ? glm::ivec2(0) : glm::ivec2(toFixed(win.x), toFixed(win.y));
}

#if RASTER_SSE2
// The frame's constants in 4 lanes, loaded once per draw (stores to the output arrays could
// alias a Frame in memory, so they would be reloaded for every vertex).
struct Frame4 {
  __m128 gx, gy, nearW, halfW, halfH, zScale, zBias;
  explicit Frame4(const Frame& f)
      : gx(_mm_set1_ps(f.gx)), gy(_mm_set1_ps(f.gy)), nearW(_mm_set1_ps(f.nearW)),
        halfW(_mm_set1_ps(f.halfW)), halfH(_mm_set1_ps(f.halfH)), zScale(_mm_set1_ps(f.zScale)),
        zBias(_mm_set1_ps(f.zBias)) {}
};

/// Bit k of the code where distance d is not >= 0 (NaN included), in 4 lanes.
RASTER_INLINE __m128i outBit(__m128 d, int k) {
  return _mm_and_si128(_mm_castps_si128(_mm_cmpnge_ps(d, _mm_setzero_ps())),
                       _mm_set1_epi32(1 << k));
}

/// outcode() of 4 vertices given by their coordinates (x, y, z, w), the same IEEE operations.
RASTER_INLINE __m128i outcode4(__m128 x, __m128 y, __m128 z, __m128 w, const Frame4& f) {
  const __m128 zero = _mm_setzero_ps();
  const __m128 gxw = rounded(_mm_mul_ps(f.gx, w)), gyw = rounded(_mm_mul_ps(f.gy, w));
  __m128i c = _mm_or_si128(outBit(_mm_add_ps(x, w), 0), outBit(_mm_sub_ps(w, x), 1));
  c = _mm_or_si128(c, _mm_or_si128(outBit(_mm_add_ps(y, w), 2), outBit(_mm_sub_ps(w, y), 3)));
  const __m128 nearD = _mm_add_ps(z, rounded(_mm_mul_ps(f.nearW, w)));
  const __m128i nearOut = _mm_or_si128(_mm_castps_si128(_mm_cmpnge_ps(nearD, zero)),
                                       _mm_castps_si128(_mm_cmpngt_ps(w, zero)));
  c = _mm_or_si128(c, _mm_and_si128(nearOut, _mm_set1_epi32(1 << kFirstPlaneBit)));
  c = _mm_or_si128(c, outBit(_mm_sub_ps(w, z), kFirstPlaneBit + 1));
  c = _mm_or_si128(c, outBit(_mm_add_ps(x, gxw), kFirstPlaneBit + 2));
  c = _mm_or_si128(c, outBit(_mm_sub_ps(gxw, x), kFirstPlaneBit + 3));
  c = _mm_or_si128(c, outBit(_mm_add_ps(y, gyw), kFirstPlaneBit + 4));
  return _mm_or_si128(c, outBit(_mm_sub_ps(gyw, y), kFirstPlaneBit + 5));
}

/// project() and toFixed() of 4 vertices, stored to win[0..3] and fixed[0..3].
RASTER_INLINE void project4(__m128 x, __m128 y, __m128 z, __m128 w, const Frame4& f,
                            glm::vec4* win, glm::ivec2* fixed) {
  const __m128 one = _mm_set1_ps(1.0f), fixedScale = _mm_set1_ps(float(kOne));
  const __m128 q = _mm_div_ps(one, w);
  __m128 wx = _mm_mul_ps(_mm_add_ps(rounded(_mm_mul_ps(x, q)), one), f.halfW);
  __m128 wy = _mm_mul_ps(_mm_add_ps(rounded(_mm_mul_ps(y, q)), one), f.halfH);
  __m128 wz = _mm_add_ps(rounded(_mm_mul_ps(_mm_mul_ps(z, q), f.zScale)), f.zBias);
  __m128 wq = q;
  const __m128i fx = _mm_cvtps_epi32(_mm_mul_ps(wx, fixedScale));
  const __m128i fy = _mm_cvtps_epi32(_mm_mul_ps(wy, fixedScale));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(&fixed[0]), _mm_unpacklo_epi32(fx, fy));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(&fixed[2]), _mm_unpackhi_epi32(fx, fy));
  _MM_TRANSPOSE4_PS(wx, wy, wz, wq);
  _mm_storeu_ps(&win[0].x, wx);
  _mm_storeu_ps(&win[1].x, wy);
  _mm_storeu_ps(&win[2].x, wz);
  _mm_storeu_ps(&win[3].x, wq);
}

/// The vertex stage of clip[0..3]: outcode4() and project4().
RASTER_INLINE void vertexStage4(const glm::vec4* clip, const Frame4& f, glm::vec4* win,
                                glm::ivec2* fixed, uint16_t* codes) {
  __m128 x = _mm_loadu_ps(&clip[0].x), y = _mm_loadu_ps(&clip[1].x);
  __m128 z = _mm_loadu_ps(&clip[2].x), w = _mm_loadu_ps(&clip[3].x);
  _MM_TRANSPOSE4_PS(x, y, z, w);
  const __m128i c = outcode4(x, y, z, w, f);
  _mm_storel_epi64(reinterpret_cast<__m128i*>(codes), _mm_packs_epi32(c, c));
  project4(x, y, z, w, f, win, fixed);
}
#endif

}  // namespace

void vertexStage(const glm::vec4* clip, size_t n, const Frame& f, glm::vec4* win,
                 glm::ivec2* fixed, uint16_t* codes) {
  size_t v = 0;
#if RASTER_SSE2
  const Frame4 f4(f);
  for (; v + 4 <= n; v += 4) vertexStage4(clip + v, f4, win + v, fixed + v, codes + v);
#endif
  for (; v < n; ++v) vertexStage1(clip[v], f, win[v], fixed[v], codes[v]);
}

}  // namespace detail

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

}  // namespace raster
