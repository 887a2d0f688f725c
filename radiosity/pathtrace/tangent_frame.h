#pragma once
// Two unit tangents completing a unit normal to an orthonormal frame (the path tracer's plane
// frames and its enclosure test's directions).
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace rad::pathtrace {

/// Unit tangents (u, v) with (u, v, n) right-handed, for unit n: u is n × the axis (x, else y)
/// least aligned with n.
inline std::pair<glm::dvec3, glm::dvec3> tangentFrame(const glm::dvec3& n) {
  const glm::dvec3 u = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  return {u, glm::cross(n, u)};
}

}  // namespace rad::pathtrace
