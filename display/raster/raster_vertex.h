// The raster core's vertex stage: outcodes and window coordinates of every vertex, once per draw.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "display/raster/raster_internal.h"

namespace raster::detail {

/// Outcode (kClipBits and the viewport bits), window coordinates (x_w, y_w, depth, 1/w) and
/// snapped window position of each of the n clip-space vertices. Where clipping bits are set
/// the window coordinates are garbage (never used) and the snapped position is 0. The same IEEE
/// operations as the clipper's tests, so both agree bit for bit on inside and outside.
void vertexStage(const glm::vec4* clip, size_t n, const Frame& f, glm::vec4* win,
                 glm::ivec2* fixed, uint16_t* codes);

}  // namespace raster::detail
