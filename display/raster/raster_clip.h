// Homogeneous clipping of the triangles that cross the near, far or guard-band planes.
#pragma once

#include <cstdint>

#include "display/raster/raster_internal.h"

namespace raster::detail {

/// Clips triangle (v[vi[0]], v[vi[1]], v[vi[2]]) against the near, far and guard-band planes
/// in double precision and rasterises the fan of what is left (the polygon's orientation
/// decides culling). Instantiated for RASTER_FOR_EACH_PIPELINE.
template <bool Fast, Shade S, bool Greater>
void clipAndDraw(const Ctx& c, const Frame& f, const Vertices& v, const uint32_t (&vi)[3]);

}  // namespace raster::detail
