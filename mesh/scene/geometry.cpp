#include "mesh/scene/geometry.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace rad {

glm::dvec3 newellNormal(const Ring& ring) {
  glm::dvec3 n(0.0);
  glm::dvec3 o = ring[0];  // relative to a vertex, so far-from-origin polygons stay exact
  for (size_t i = 0; i < ring.size(); ++i) {
    glm::dvec3 a = ring[i] - o, b = ring[(i + 1) % ring.size()] - o;
    n += glm::cross(a, b);
  }
  return n;
}

glm::dvec2 PlaneFrame::project(const glm::dvec3& p) const {
  glm::dvec3 d = p - origin;
  return {glm::dot(d, u), glm::dot(d, v)};
}

glm::dvec3 PlaneFrame::lift(const glm::dvec2& q) const { return origin + q.x * u + q.y * v; }

namespace {

/// An axis far from parallel to the unit normal n: u is taken across it, for a
/// well-conditioned frame.
glm::dvec3 crossAxis(const glm::dvec3& n) {
  return std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : std::abs(n.y) < 0.6 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
}

}  // namespace

PlaneFrame planeFrame(const Ring& ring) {
  glm::dvec3 origin(0.0);
  for (const auto& p : ring) origin += p;
  origin /= double(ring.size());
  glm::dvec3 n = newellNormal(ring);
  double len = glm::length(n);
  return planeFrame(origin, len > 0 ? n / len : glm::dvec3(0, 0, 1));
}

PlaneFrame planeFrame(const glm::dvec3& origin, const glm::dvec3& normal) {
  PlaneFrame f;
  f.origin = origin;
  f.normal = normal;
  f.u = glm::normalize(glm::cross(crossAxis(f.normal), f.normal));
  f.v = glm::cross(f.normal, f.u);
  return f;
}

std::vector<size_t> convexHull(const std::vector<glm::dvec2>& points) {
  std::vector<size_t> order(points.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (points.size() < 3) return order;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::make_pair(points[a].x, points[a].y) < std::make_pair(points[b].x, points[b].y);
  });
  auto turn = [&](size_t o, size_t a, size_t b) {
    return (points[a].x - points[o].x) * (points[b].y - points[o].y) -
           (points[a].y - points[o].y) * (points[b].x - points[o].x);
  };
  std::vector<size_t> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < order.size(); ++i) {  // lower chain
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], order[i]) <= 0) --k;
    hull[k++] = order[i];
  }
  for (size_t i = order.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && turn(hull[k - 2], hull[k - 1], order[i]) <= 0) --k;
    hull[k++] = order[i];
  }
  hull.resize(k - 1);  // the last corner is the first
  return hull;
}

double triangleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

double angleDeg(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 u = b - a, v = c - a;
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v)) * 180 / M_PI;
}

std::vector<std::array<glm::dvec3, 3>> congruentSplit(const std::array<glm::dvec3, 3>& t, int m) {
  std::vector<std::array<glm::dvec3, 3>> out;
  out.reserve(size_t(m) * size_t(m));
  const glm::dvec3 u = (t[1] - t[0]) / double(m), v = (t[2] - t[0]) / double(m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; i + j < m; ++j) {
      const glm::dvec3 p = t[0] + double(i) * u + double(j) * v;
      out.push_back({p, p + u, p + v});
      if (i + j + 1 < m) out.push_back({p + u, p + u + v, p + v});
    }
  return out;
}

double median(std::vector<double> values) {
  if (values.empty()) return HUGE_VAL;
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

double polygonArea(const Polygon& polygon) {
  glm::dvec3 n = newellNormal(polygon.outer);
  double len = glm::length(n);
  if (len == 0) return 0.0;
  glm::dvec3 unit = n / len;
  double area = 0.5 * len;
  for (const auto& hole : polygon.holes) area -= 0.5 * std::abs(glm::dot(newellNormal(hole), unit));
  return area;
}

double ringDiameter(const Ring& ring) {
  double d = 0;
  for (size_t i = 0; i < ring.size(); ++i)
    for (size_t j = i + 1; j < ring.size(); ++j) d = std::max(d, glm::length(ring[i] - ring[j]));
  return d;
}

double maxPlaneDistance(const PlaneFrame& frame, const Ring& ring) {
  double d = 0;
  for (const auto& p : ring) d = std::max(d, std::abs(glm::dot(p - frame.origin, frame.normal)));
  return d;
}

double segmentDistance(const glm::dvec2& q, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 d = b - a;
  const double t = std::clamp(glm::dot(q - a, d) / glm::dot(d, d), 0.0, 1.0);
  return glm::length(a + d * t - q);
}

bool insideRing(const PlaneFrame& frame, const Ring& ring, const glm::dvec3& p) {
  glm::dvec2 q = frame.project(p);
  bool inside = false;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    glm::dvec2 a = frame.project(ring[i]), b = frame.project(ring[j]);
    if ((a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y))
      inside = !inside;
  }
  return inside;
}

bool insidePolygon(const PlaneFrame& frame, const Polygon& polygon, const glm::dvec3& p) {
  bool inside = insideRing(frame, polygon.outer, p);
  for (const Ring& hole : polygon.holes) inside = inside != insideRing(frame, hole, p);
  return inside;
}

}  // namespace rad
