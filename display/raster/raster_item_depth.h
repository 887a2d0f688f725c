// The item+depth path's 4-pixel step (SSE2): depth test and write, item write, in one blend.
#pragma once

#include <cstdint>

#include "display/raster/raster_internal.h"

#if RASTER_SSE2
namespace raster::detail {

/// Depth clamp of 4 lanes to [0, 1] (clampDepth() bit for bit).
RASTER_INLINE __m128 clampDepth4(__m128 z) {
  return _mm_min_ps(_mm_max_ps(z, _mm_setzero_ps()), _mm_set1_ps(1.0f));
}

/// Depth test (LESS, or GREATER for reversed depth) of depths z against d[0..3], among the
/// lanes set in `in` (all ones or all zeros); the passing lanes get depth z and item `id`
/// (all lanes), the others are rewritten with their own values.
template <bool Greater>
RASTER_INLINE void blendItemDepth(float* d, uint32_t* it, __m128 z, __m128 in, __m128i id) {
  const __m128 dOld = _mm_loadu_ps(d);
  const __m128 pass = _mm_and_ps(Greater ? _mm_cmplt_ps(dOld, z) : _mm_cmplt_ps(z, dOld), in);
  _mm_storeu_ps(d, _mm_or_ps(_mm_and_ps(pass, z), _mm_andnot_ps(pass, dOld)));
  const __m128i p = _mm_castps_si128(pass);
  const __m128i iOld = _mm_loadu_si128(reinterpret_cast<const __m128i*>(it));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(it),
                   _mm_or_si128(_mm_and_si128(p, id), _mm_andnot_si128(p, iOld)));
}

}  // namespace raster::detail
#endif
