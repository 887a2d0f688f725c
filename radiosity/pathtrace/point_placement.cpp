// Where the reference measures: points on the surfaces, by area and near edges and contacts.
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>

#include "radiosity/pathtrace/path_tracer.h"

namespace rad::pathtrace {
namespace {

/// Shares of placed points near the surfaces' own edges and near contact lines.
constexpr double kEdgeShare = 0.125, kContactShare = 0.125;
/// Their distance from the edge: log-uniform between these (normalised units).
constexpr double kNearest = 1e-3, kFarthest = 3e-2;
/// An edge of another surface lies on a polygon when both ends are this close to its plane.
constexpr double kOnPlane = 1e-6;
/// Rays that decide whether a point lies inside a solid, and the tries per point.
constexpr int kEnclosureRays = 16;
constexpr int kTries = 64;
/// Above this many (edge, polygon) pairs contact lines are not looked for (edges only).
constexpr double kMaxContactPairs = 5e7;
/// Located points lie within this (normalised) distance of their surface.
constexpr double kLocateTolerance = 1e-4;

/// A stretch of line near which points go: on `surface`, in the plane with normal `normal`.
struct Segment {
  glm::dvec3 a{0.0}, b{0.0}, normal{0.0};
  int surface = -1;
  bool contact = false;  ///< another surface's edge lying on this one
};

/// The polygon's plane: a point and the unit normal (Newell's), normalised coordinates.
std::pair<glm::dvec3, glm::dvec3> planeOf(const TraceScene& scene, const Ring& ring) {
  glm::dvec3 n(0.0);
  for (size_t i = 0; i < ring.size(); ++i)
    n += glm::cross(scene.toLocal(ring[i]), scene.toLocal(ring[(i + 1) % ring.size()]));
  return {scene.toLocal(ring[0]), glm::length(n) > 0 ? glm::normalize(n) : n};
}

bool emits(const TraceScene& scene, int surface) { return scene.material(surface).emits(); }

/// Every surface's boundary edges (edges not shared by two of its polygons), with the normal
/// of the polygon they bound.
std::vector<Segment> boundaryEdges(const TraceScene& scene) {
  std::vector<Segment> out;
  const Scene& s = scene.scene();
  for (size_t i = 0; i < s.surfaces.size(); ++i) {
    using Key = std::pair<std::tuple<double, double, double>, std::tuple<double, double, double>>;
    std::map<Key, int> uses;
    std::vector<std::pair<Key, Segment>> edges;  // keyed by the scene's own coordinates
    auto key = [](const glm::dvec3& p, const glm::dvec3& q) -> Key {
      auto u = std::make_tuple(p.x, p.y, p.z), v = std::make_tuple(q.x, q.y, q.z);
      return u < v ? Key{u, v} : Key{v, u};
    };
    for (const auto& polygon : s.surfaces[i].polygons) {
      const glm::dvec3 n = planeOf(scene, polygon.outer).second;
      std::vector<const Ring*> rings{&polygon.outer};
      for (const auto& h : polygon.holes) rings.push_back(&h);
      for (const Ring* ring : rings)
        for (size_t k = 0; k < ring->size(); ++k) {
          const glm::dvec3 a = (*ring)[k], b = (*ring)[(k + 1) % ring->size()];
          if (a == b) continue;
          ++uses[key(a, b)];
          edges.push_back({key(a, b), {scene.toLocal(a), scene.toLocal(b), n, int(i)}});
        }
    }
    for (const auto& [k, e] : edges)
      if (uses[k] == 1) out.push_back(e);
  }
  return out;
}

/// Where points near edges go: each non-emitting surface's own boundary edges, and the
/// boundary edges of other surfaces that lie on one of its polygons (contact lines).
std::vector<Segment> edgeSegments(const TraceScene& scene) {
  const std::vector<Segment> edges = boundaryEdges(scene);
  std::vector<Segment> out;
  for (const auto& e : edges)
    if (!emits(scene, e.surface)) out.push_back(e);
  const Scene& s = scene.scene();
  size_t polygons = 0;
  for (const auto& surface : s.surfaces) polygons += surface.polygons.size();
  if (double(edges.size()) * double(polygons) > kMaxContactPairs) return out;
  for (size_t i = 0; i < s.surfaces.size(); ++i) {
    if (emits(scene, int(i))) continue;
    for (const auto& polygon : s.surfaces[i].polygons) {
      const auto [origin, n] = planeOf(scene, polygon.outer);
      for (const auto& e : edges)
        if (e.surface != int(i) && std::abs(glm::dot(e.a - origin, n)) < kOnPlane &&
            std::abs(glm::dot(e.b - origin, n)) < kOnPlane)
          out.push_back({e.a, e.b, n, int(i), true});
    }
  }
  return out;
}

/// Whether every direction from p ends on the back of a one-sided surface: p is inside a solid.
bool enclosed(const TraceScene& scene, const glm::dvec3& p, const glm::dvec3& n, Random& rng) {
  const glm::dvec3 t = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 s = glm::cross(n, t);
  for (int k = 0; k < kEnclosureRays; ++k) {
    const double r = std::sqrt(rng.next()), phi = 6.283185307179586 * rng.next();
    const glm::dvec3 w = r * std::cos(phi) * t + r * std::sin(phi) * s + std::sqrt(std::max(0.0, 1 - r * r)) * n;
    const TraceHit hit = scene.intersect(p + kRayOffset * n, w, HUGE_VAL);
    if (hit.triangle < 0 || hit.front || scene.twoSided(scene.triangles()[size_t(hit.triangle)].surface))
      return false;
  }
  return true;
}

/// The point q (normalised) on `surface`'s side facing n, if it lies on that surface, outside
/// holes and outside solids.
bool accept(const TraceScene& scene, const glm::dvec3& q, const glm::dvec3& n, int surface,
            Random& rng, std::vector<SurfacePoint>& out, const char* tag) {
  SurfacePoint p{scene.toScene(q), n, -1, tag};
  if (!locatePoint(scene, p, kLocateTolerance * scene.size()) || p.surface != surface) return false;
  if (enclosed(scene, scene.toLocal(p.position), p.normal, rng)) return false;
  out.push_back(p);
  return true;
}

/// An entry of the area table: triangle t on the side facing `sign`·normal.
struct AreaEntry {
  int triangle;
  double sign;
};

void placeByArea(const TraceScene& scene, int count, Random& rng, std::vector<SurfacePoint>& out) {
  std::vector<AreaEntry> entries;
  std::vector<double> cdf;
  double total = 0;
  const auto& tris = scene.triangles();
  for (size_t t = 0; t < tris.size(); ++t) {
    if (emits(scene, tris[t].surface)) continue;
    for (double sign : {1.0, -1.0}) {
      if (sign < 0 && !scene.twoSided(tris[t].surface)) continue;
      entries.push_back({int(t), sign});
      cdf.push_back(total += tris[t].area);
    }
  }
  if (entries.empty()) return;
  for (int i = 0; i < count; ++i) {
    // Stratified by area; a point that falls in a hole or a solid is drawn again anywhere.
    for (int attempt = 0; attempt < kTries; ++attempt) {
      const double u = attempt == 0 ? (i + rng.next()) / count : rng.next();
      const size_t k = std::min(entries.size() - 1, size_t(std::upper_bound(cdf.begin(), cdf.end(), u * total) - cdf.begin()));
      const TraceTriangle& t = tris[size_t(entries[k].triangle)];
      const glm::dvec3 q = scene.pointOn(entries[k].triangle, rng.next(), rng.next());
      if (accept(scene, q, entries[k].sign * t.normal, t.surface, rng, out, "area")) break;
    }
  }
}

/// Points near the given segments, tagged `tag`.
void placeNear(const TraceScene& scene, const std::vector<Segment>& segments, int count, const char* tag,
               Random& rng, std::vector<SurfacePoint>& out) {
  std::vector<double> cdf;
  double total = 0;
  for (const auto& s : segments) cdf.push_back(total += glm::length(s.b - s.a));
  if (segments.empty()) return;
  for (int i = 0; i < count; ++i)
    for (int attempt = 0; attempt < kTries; ++attempt) {
      const double u = attempt == 0 ? (i + rng.next()) / count : rng.next();
      const Segment& s = segments[std::min(segments.size() - 1, size_t(std::upper_bound(cdf.begin(), cdf.end(), u * total) - cdf.begin()))];
      const glm::dvec3 along = s.a + rng.next() * (s.b - s.a);
      const double d = kNearest * std::pow(kFarthest / kNearest, rng.next());
      const glm::dvec3 across = glm::normalize(glm::cross(s.normal, s.b - s.a));
      const double side = rng.next() < 0.5 ? 1 : -1;
      const bool twoSided = scene.twoSided(s.surface);
      const glm::dvec3 n = (twoSided && rng.next() < 0.5) ? -s.normal : s.normal;
      if (accept(scene, along + side * d * across, n, s.surface, rng, out, tag) ||
          accept(scene, along - side * d * across, n, s.surface, rng, out, tag))
        break;
    }
}

}  // namespace

std::vector<SurfacePoint> placePoints(const TraceScene& scene, int count, uint64_t seed) {
  Random rng = Random::stream(seed, ~0ull);
  std::vector<SurfacePoint> out;
  std::vector<Segment> edges, contacts;
  for (const auto& s : edgeSegments(scene)) (s.contact ? contacts : edges).push_back(s);
  const int nearContacts = contacts.empty() ? 0 : int(std::lround(count * kContactShare));
  const int nearEdges = int(std::lround(count * (kEdgeShare + kContactShare))) - nearContacts;
  placeByArea(scene, count - nearEdges - nearContacts, rng, out);
  placeNear(scene, edges, nearEdges, "edge", rng, out);
  placeNear(scene, contacts, nearContacts, "contact", rng, out);
  return out;
}

bool locatePoint(const TraceScene& scene, SurfacePoint& point, double tolerance) {
  const glm::dvec3 n = glm::normalize(point.normal);
  const double reach = tolerance / scene.size();
  const glm::dvec3 from = scene.toLocal(point.position) + reach * n;
  const TraceHit hit = scene.intersect(from, -n, 2 * reach);
  if (hit.triangle < 0) return false;
  const TraceTriangle& t = scene.triangles()[size_t(hit.triangle)];
  if (!hit.front && !scene.twoSided(t.surface)) return false;  // the back of a one-sided surface
  point.surface = t.surface;
  point.position = scene.toScene(hit.point);
  point.normal = hit.front ? t.normal : -t.normal;
  return true;
}

}  // namespace rad::pathtrace
