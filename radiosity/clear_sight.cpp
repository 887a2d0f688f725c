#include "radiosity/clear_sight.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

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
  glm::dvec3 normal(0.0), centroid(0.0);
  for (const glm::dvec3& corner : base) centroid += corner;
  centroid /= double(base.size());
  for (size_t i = 0; i < base.size(); ++i)  // relative to the centroid: exact far from the origin too
    normal += glm::cross(base[i] - centroid, base[(i + 1) % base.size()] - centroid);
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

std::vector<glm::dvec3> planarConvexHull(const std::vector<glm::dvec3>& points, const glm::dvec3& normal) {
  if (points.size() < 3) return points;
  // Coordinates (u, v) in the plane, v = normal × u: counter-clockwise there is
  // counter-clockwise seen from the normal's side. Andrew's monotone chain.
  const glm::dvec3 u = glm::normalize(std::abs(normal.x) < 0.9 ? glm::cross(normal, glm::dvec3(1, 0, 0))
                                                               : glm::cross(normal, glm::dvec3(0, 1, 0)));
  const glm::dvec3 v = glm::cross(normal, u);
  struct Point2 {
    double u, v;
    size_t index;
  };
  std::vector<Point2> p;
  p.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) p.push_back({glm::dot(points[i], u), glm::dot(points[i], v), i});
  std::sort(p.begin(), p.end(),
            [](const Point2& a, const Point2& b) { return a.u < b.u || (a.u == b.u && a.v < b.v); });
  auto turn = [](const Point2& o, const Point2& a, const Point2& b) {
    return (a.u - o.u) * (b.v - o.v) - (a.v - o.v) * (b.u - o.u);
  };
  std::vector<Point2> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {  // lower chain
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && turn(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);  // the last point is the first
  std::vector<glm::dvec3> out;
  out.reserve(hull.size());
  for (const Point2& q : hull) out.push_back(points[q.index]);
  return out;
}

}  // namespace rad
