// Rasterisation of one snapped triangle: exact 64-bit edge functions, top-left fill rule.
#pragma once

#include <cstdint>

#include "display/raster/raster_internal.h"

namespace raster::detail {

/// Rasterises the counter-clockwise snapped triangle (v0, v1, v2), area = area2(v0, v1, v2) > 0,
/// into the buffers of `c` with its current id (and flat colour). Fast: the item+depth path;
/// S: colour interpolation; Greater: depth test GREATER instead of LESS. Instantiated for
/// RASTER_FOR_EACH_PIPELINE.
template <bool Fast, Shade S, bool Greater>
void rasterTriangle(const Ctx& c, const SVert& v0, const SVert& v1, const SVert& v2, int64_t area);

/// Orients (or culls) a snapped triangle and rasterises it.
template <bool Fast, Shade S, bool Greater>
inline void drawSnapped(const Ctx& c, const SVert& v0, const SVert& v1, const SVert& v2) {
  const int64_t a = area2(v0, v1, v2);
  if (a > 0)
    rasterTriangle<Fast, S, Greater>(c, v0, v1, v2, a);
  else if (a < 0 && !c.cullBack)
    rasterTriangle<Fast, S, Greater>(c, v0, v2, v1, -a);
}

}  // namespace raster::detail
