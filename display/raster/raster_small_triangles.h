// The item+depth path's triangle loop (SSE2), with its own setup for small triangles.
#pragma once

#include "display/raster/raster_internal.h"

#if RASTER_SSE2
namespace raster::detail {

/// Draws triangles t into c's depth and item buffers (depth test and write on, no colour, no
/// hits): the pipeline of the generic path, bit for bit, with the unclipped triangles set up
/// straight from the vertex stage's arrays. Greater: depth test GREATER instead of LESS.
template <bool Greater>
void drawAllFast(Ctx& c, const Frame& f, const Vertices& v, const Triangles& t);

}  // namespace raster::detail
#endif
