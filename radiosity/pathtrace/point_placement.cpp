// Where the reference measures: points on the surfaces, by area and near edges and contacts.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include <glm/geometric.hpp>

#include "radiosity/pathtrace/path_tracer.h"
#include "radiosity/pathtrace/tangent_frame.h"

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
/// locatePoint looks at this many surfaces along a point's normal at most, stepping this far
/// (in units of the scene's size) past each.
constexpr int kMaxCrossings = 16;
constexpr double kCrossingStep = 1e-6;  // above single precision's round-off at the scene's size

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

/// Whether the surface emits (no points are placed on emitters).
bool emits(const TraceScene& scene, int surface) { return scene.material(surface).emits(); }

/// A corner in the scene's own coordinates, and an edge as its two corners in order.
using Corner = std::tuple<double, double, double>;
using EdgeKey = std::pair<Corner, Corner>;

/// The edge (p, q) as a key, the same both ways round.
EdgeKey edgeKey(const glm::dvec3& p, const glm::dvec3& q) {
  const Corner u = std::make_tuple(p.x, p.y, p.z), v = std::make_tuple(q.x, q.y, q.z);
  return u < v ? EdgeKey{u, v} : EdgeKey{v, u};
}

/// The edges of one ring of a polygon with normal n on `surface`, each with its key.
void addRingEdges(const TraceScene& scene, const Ring& ring, const glm::dvec3& n, int surface,
                  std::vector<std::pair<EdgeKey, Segment>>& edges) {
  for (size_t k = 0; k < ring.size(); ++k) {
    const glm::dvec3 a = ring[k], b = ring[(k + 1) % ring.size()];
    if (a != b) edges.push_back({edgeKey(a, b), {scene.toLocal(a), scene.toLocal(b), n, surface}});
  }
}

/// Every edge of a surface's polygons (outer rings and holes), with the normal of the polygon
/// it bounds: an edge two of its polygons share comes twice.
std::vector<std::pair<EdgeKey, Segment>> surfaceEdges(const TraceScene& scene, int surface) {
  std::vector<std::pair<EdgeKey, Segment>> edges;
  for (const auto& polygon : scene.scene().surfaces[size_t(surface)].polygons) {
    const glm::dvec3 n = planeOf(scene, polygon.outer).second;
    addRingEdges(scene, polygon.outer, n, surface, edges);
    for (const auto& h : polygon.holes) addRingEdges(scene, h, n, surface, edges);
  }
  return edges;
}

/// Every surface's boundary edges (edges not shared by two of its polygons), with the normal
/// of the polygon they bound.
std::vector<Segment> boundaryEdges(const TraceScene& scene) {
  std::vector<Segment> out;
  for (size_t i = 0; i < scene.scene().surfaces.size(); ++i) {
    const auto edges = surfaceEdges(scene, int(i));
    std::map<EdgeKey, int> uses;
    for (const auto& e : edges) ++uses[e.first];
    for (const auto& [k, e] : edges)
      if (uses[k] == 1) out.push_back(e);
  }
  return out;
}

/// How many polygons the scene's surfaces have in all.
size_t polygonCount(const Scene& s) {
  size_t polygons = 0;
  for (const auto& surface : s.surfaces) polygons += surface.polygons.size();
  return polygons;
}

/// Whether segment e lies in the plane through `origin` with unit normal n.
bool liesOn(const Segment& e, const glm::dvec3& origin, const glm::dvec3& n) {
  return std::abs(glm::dot(e.a - origin, n)) < kOnPlane && std::abs(glm::dot(e.b - origin, n)) < kOnPlane;
}

/// The contact lines on `surface`: other surfaces' boundary edges lying on one of its polygons.
void addContacts(const TraceScene& scene, const std::vector<Segment>& edges, int surface, std::vector<Segment>& out) {
  for (const auto& polygon : scene.scene().surfaces[size_t(surface)].polygons) {
    const auto [origin, n] = planeOf(scene, polygon.outer);
    for (const auto& e : edges)
      if (e.surface != surface && liesOn(e, origin, n)) out.push_back({e.a, e.b, n, surface, true});
  }
}

/// Where points near edges go: each non-emitting surface's own boundary edges, and the
/// boundary edges of other surfaces that lie on one of its polygons (contact lines).
std::vector<Segment> edgeSegments(const TraceScene& scene) {
  const std::vector<Segment> edges = boundaryEdges(scene);
  std::vector<Segment> out;
  for (const auto& e : edges)
    if (!emits(scene, e.surface)) out.push_back(e);
  const Scene& s = scene.scene();
  if (double(edges.size()) * double(polygonCount(s)) > kMaxContactPairs) return out;
  for (size_t i = 0; i < s.surfaces.size(); ++i)
    if (!emits(scene, int(i))) addContacts(scene, edges, int(i), out);
  return out;
}

/// A cosine-weighted direction about unit n in the frame (t, s, n).
glm::dvec3 cosineDirection(const glm::dvec3& t, const glm::dvec3& s, const glm::dvec3& n, Random& rng) {
  const double r = std::sqrt(rng.next()), phi = 6.283185307179586 * rng.next();
  return r * std::cos(phi) * t + r * std::sin(phi) * s + std::sqrt(std::max(0.0, 1 - r * r)) * n;
}

/// Whether every direction from p ends on the back of a one-sided surface: p is inside a solid.
bool enclosed(const TraceScene& scene, const glm::dvec3& p, const glm::dvec3& n, Random& rng) {
  const auto [t, s] = tangentFrame(n);
  for (int k = 0; k < kEnclosureRays; ++k) {
    const TraceHit hit = scene.intersect(p + kRayOffset * n, cosineDirection(t, s, n, rng), HUGE_VAL);
    if (hit.triangle < 0 || scene.reflects(hit)) return false;
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

/// The entry whose share of the cumulative table `cdf` holds x.
size_t pick(const std::vector<double>& cdf, double x) {
  return std::min(cdf.size() - 1, size_t(std::upper_bound(cdf.begin(), cdf.end(), x) - cdf.begin()));
}

/// Where draw `attempt` of point i of `count` falls in [0, 1): stratified on the first
/// attempt, anywhere on the next ones.
double stratified(int i, int count, int attempt, Random& rng) {
  return attempt == 0 ? (i + rng.next()) / count : rng.next();
}

/// An entry of the area table: triangle t on the side facing `sign`·normal.
struct AreaEntry {
  int triangle;
  double sign;
};

/// The non-emitting triangles' sides (both for two-sided surfaces) and their cumulative area.
struct AreaTable {
  std::vector<AreaEntry> entries;
  std::vector<double> cdf;
  double total = 0;

  explicit AreaTable(const TraceScene& scene) {
    const auto& tris = scene.triangles();
    for (size_t t = 0; t < tris.size(); ++t)
      if (!emits(scene, tris[t].surface)) {
        add(int(t), 1.0, tris[t].area);
        if (scene.twoSided(tris[t].surface)) add(int(t), -1.0, tris[t].area);
      }
  }

  /// Adds triangle t's side facing sign·normal.
  void add(int t, double sign, double area) {
    entries.push_back({t, sign});
    cdf.push_back(total += area);
  }
};

/// Stratified by area; a point that falls in a hole or a solid is drawn again anywhere.
void placeByArea(const TraceScene& scene, int count, Random& rng, std::vector<SurfacePoint>& out) {
  const AreaTable table(scene);
  if (table.entries.empty()) return;
  for (int i = 0; i < count; ++i)
    for (int attempt = 0; attempt < kTries; ++attempt) {
      const AreaEntry& e = table.entries[pick(table.cdf, stratified(i, count, attempt, rng) * table.total)];
      const TraceTriangle& t = scene.triangle(e.triangle);
      const double v = rng.next(), u = rng.next();  // one draw each, in a fixed order
      const glm::dvec3 q = scene.pointOn(e.triangle, u, v);
      if (accept(scene, q, e.sign * t.normal, t.surface, rng, out, "area")) break;
    }
}

/// One try at a point near segment s, at a log-uniform distance on either side of it.
bool placeNear(const TraceScene& scene, const Segment& s, const char* tag, Random& rng,
               std::vector<SurfacePoint>& out) {
  const glm::dvec3 along = s.a + rng.next() * (s.b - s.a);
  const double d = kNearest * std::pow(kFarthest / kNearest, rng.next());
  const glm::dvec3 across = glm::normalize(glm::cross(s.normal, s.b - s.a));
  const double side = rng.next() < 0.5 ? 1 : -1;
  const bool twoSided = scene.twoSided(s.surface);
  const glm::dvec3 n = (twoSided && rng.next() < 0.5) ? -s.normal : s.normal;
  return accept(scene, along + side * d * across, n, s.surface, rng, out, tag) ||
         accept(scene, along - side * d * across, n, s.surface, rng, out, tag);
}

/// Points near the given segments, tagged `tag`.
void placeNear(const TraceScene& scene, const std::vector<Segment>& segments, int count, const char* tag,
               Random& rng, std::vector<SurfacePoint>& out) {
  std::vector<double> cdf;
  double total = 0;
  for (const auto& s : segments) cdf.push_back(total += glm::length(s.b - s.a));
  if (segments.empty()) return;
  for (int i = 0; i < count; ++i)
    for (int attempt = 0; attempt < kTries; ++attempt)
      if (placeNear(scene, segments[pick(cdf, stratified(i, count, attempt, rng) * total)], tag, rng, out)) break;
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
  const glm::dvec3 at = scene.toLocal(point.position);
  // Every surface crossed on the normal's line within reach on either side, the nearest to the
  // point whose lit side faces the normal's way kept: another surface just in front (a narrow
  // gap, a lamp under a ceiling) or just behind (a tread through a wall) is passed over.
  std::optional<TraceHit> best;
  double bestDistance = HUGE_VAL, travelled = 0;
  glm::dvec3 from = at + reach * n;
  for (int crossing = 0; crossing < kMaxCrossings && travelled < 2 * reach; ++crossing) {
    const TraceHit hit = scene.intersect(from, -n, 2 * reach - travelled);
    if (hit.triangle < 0) break;
    const double distance = std::abs(glm::dot(hit.point - at, n));
    if (scene.reflects(hit) && distance < bestDistance)  // the side met faces the normal's way
      best = hit, bestDistance = distance;
    travelled += glm::length(hit.point - from) + kCrossingStep;
    from = hit.point - kCrossingStep * n;
  }
  if (!best) return false;
  point.surface = scene.triangle(best->triangle).surface;
  point.position = scene.toScene(best->point);
  point.normal = scene.sideNormal(*best);
  return true;
}

}  // namespace rad::pathtrace
