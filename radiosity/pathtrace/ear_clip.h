#pragma once
// Triangulation of the path tracer's polygons: ear clipping of a simple ring in its plane.
#include <array>
#include <vector>

#include <glm/vec2.hpp>

namespace rad::pathtrace {

/// Ear clipping of a simple ring given counter-clockwise in 2D: triangles as index triples.
/// Where rounding leaves no clean ear, the most convex corner is clipped, so it always ends.
std::vector<std::array<int, 3>> earClip(const std::vector<glm::dvec2>& pts);

}  // namespace rad::pathtrace
