#include "radiosity/light/clear_sight.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/scene/geometry.h"

namespace rad {
namespace {

/// A base edge seen from the apex under an angle below this (radians) bounds no side plane.
constexpr double kShortestEdge = 1e-9;

}  // namespace

bool ClearSight::pyramid(const glm::dvec3& apex, const std::vector<glm::dvec3>& base,
                         std::vector<Plane>& planes) const {
  planes.clear();
  if (base.size() < 3) return false;
  // The base's plane by Newell's sum (any convex polygon, either way round), facing the apex.
  glm::dvec3 normal = newellNormal(base), centroid(0.0);
  for (const glm::dvec3& corner : base) centroid += corner;
  centroid /= double(base.size());
  const double length = glm::length(normal);
  if (!(length > 0)) return false;
  normal /= length;
  const double height = glm::dot(normal, apex - centroid);
  if (!(std::abs(height) > margin_)) return false;
  if (height < 0) normal = -normal;
  planes.push_back({-normal, glm::dot(-normal, centroid)});
  // A side plane through the apex and each edge, facing away from the base's centroid. An
  // edge too short for its plane's direction to mean anything gets none (a larger pyramid).
  for (size_t i = 0; i < base.size(); ++i) {
    const glm::dvec3 a = base[i] - apex, b = base[(i + 1) % base.size()] - apex;
    glm::dvec3 n = glm::cross(a, b);
    const double l = glm::length(n);
    if (!(l > kShortestEdge * glm::length(a) * glm::length(b))) continue;
    n /= l;
    if (glm::dot(n, centroid - apex) > 0) n = -n;
    planes.push_back({n, glm::dot(n, apex)});
  }
  return true;
}

bool ClearSight::apart(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& normal,
                       const glm::dvec3& apex, const std::vector<glm::dvec3>& base,
                       const std::vector<Plane>& planes) const {
  // The triangle's own plane first (the pyramid is the hull of its corners): it separates
  // the surface the point lies on, whose elements crowd round the apex.
  const double side = glm::dot(normal, apex - a);
  if (std::abs(side) > margin_) {
    bool separates = true;
    for (const glm::dvec3& corner : base) {
      const double s = glm::dot(normal, corner - a);
      if (!(side > 0 ? s > margin_ : s < -margin_)) {
        separates = false;
        break;
      }
    }
    if (separates) return true;
  }
  for (const Plane& plane : planes) {
    const double limit = plane.offset + margin_;
    const glm::dvec3& n = plane.normal;
    if (glm::dot(n, a) > limit && glm::dot(n, b) > limit && glm::dot(n, c) > limit) return true;
  }
  return false;
}

bool ClearSight::clear(const glm::dvec3& apex, const std::vector<glm::dvec3>& base) const {
  thread_local std::vector<Plane> planes;
  thread_local std::vector<uint32_t> stack;
  if (!pyramid(apex, base, planes)) return false;
  const auto& nodes = occluders_.nodes();
  // A box apart from the pyramid's own box, or outside one of its planes (when its corner
  // least far along the plane's normal is).
  glm::dvec3 lo = apex, hi = apex;
  for (const glm::dvec3& corner : base) lo = glm::min(lo, corner), hi = glm::max(hi, corner);
  lo -= glm::dvec3(margin_), hi += glm::dvec3(margin_);
  auto boxOutside = [&](const ElementHierarchy::Node& node) {
    if (node.lo.x > hi.x || node.lo.y > hi.y || node.lo.z > hi.z || node.hi.x < lo.x || node.hi.y < lo.y ||
        node.hi.z < lo.z)
      return true;
    for (const Plane& plane : planes) {
      double nearest = 0;
      for (int k = 0; k < 3; ++k) nearest += plane.normal[k] * (plane.normal[k] > 0 ? node.lo[k] : node.hi[k]);
      if (nearest > plane.offset + margin_) return true;
    }
    return false;
  };
  stack.assign(1, 0);
  while (!stack.empty()) {
    const uint32_t k = stack.back();
    stack.pop_back();
    const ElementHierarchy::Node& node = nodes[k];
    if (boxOutside(node)) continue;
    if (!node.leaf()) {
      stack.push_back(node.second);
      stack.push_back(k + 1);
      continue;
    }
    const glm::dvec3* at = occluders_.leafPositions().data() + node.vertexFirst;
    for (uint32_t i = node.first; i < node.first + node.count; ++i) {
      const auto& c = occluders_.corners()[i];
      if (!apart(at[c[0]], at[c[1]], at[c[2]], occluders_.normals()[i], apex, base, planes)) return false;
    }
  }
  return true;
}

}  // namespace rad
