#include "radiosity/pathtrace/trace_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

namespace rad::pathtrace {
namespace {

/// Newell's normal of a ring (not normalised): robust for non-planar and concave rings.
glm::dvec3 newellNormal(const Ring& ring) {
  glm::dvec3 n(0.0);
  for (size_t i = 0; i < ring.size(); ++i) {
    const glm::dvec3 &p = ring[i], &q = ring[(i + 1) % ring.size()];
    n += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
  }
  return n;
}

double cross2(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

bool insideTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return cross2(a, b, p) > 0 && cross2(b, c, p) > 0 && cross2(c, a, p) > 0;
}

double angleAt(const glm::dvec2& p, const glm::dvec2& at, const glm::dvec2& q) {
  const glm::dvec2 u = p - at, v = q - at;
  return std::atan2(std::abs(u.x * v.y - u.y * v.x), u.x * v.x + u.y * v.y);
}

/// Whether no other corner of the ring lies inside triangle (p, c, q).
bool emptyTriangle(const std::vector<glm::dvec2>& pts, const std::vector<int>& ring, int p, int c, int q) {
  bool empty = true;
  for (size_t j = 0; j < ring.size() && empty; ++j) {
    const int k = ring[j];
    if (k != p && k != c && k != q) empty = !insideTriangle(pts[k], pts[p], pts[c], pts[q]);
  }
  return empty;
}

/// The corner of the ring to clip: the first ear, else the most convex corner.
size_t nextEar(const std::vector<glm::dvec2>& pts, const std::vector<int>& ring) {
  const size_t n = ring.size();
  int best = -1;
  double bestTurn = -HUGE_VAL;
  for (size_t i = 0; i < n; ++i) {
    const int p = ring[(i + n - 1) % n], c = ring[i], q = ring[(i + 1) % n];
    const double turn = cross2(pts[p], pts[c], pts[q]);
    if (turn > bestTurn) bestTurn = turn, best = int(i);
    if (turn <= 0) continue;
    if (emptyTriangle(pts, ring, p, c, q)) return i;
  }
  return size_t(best);
}

/// Ear clipping of a simple ring given counter-clockwise in 2D: triangles as index triples.
/// Where rounding leaves no clean ear, the most convex corner is clipped, so it always ends.
std::vector<std::array<int, 3>> earClip(const std::vector<glm::dvec2>& pts) {
  std::vector<int> ring(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) ring[i] = int(i);
  std::vector<std::array<int, 3>> out;
  // A quad (a bent wall is one) takes its Delaunay diagonal: the angles facing it sum to at
  // most π. The same polygon meshed elsewhere then bends along the same line.
  if (pts.size() == 4 && cross2(pts[0], pts[1], pts[2]) > 0 && cross2(pts[2], pts[3], pts[0]) > 0 &&
      angleAt(pts[0], pts[1], pts[2]) + angleAt(pts[2], pts[3], pts[0]) <= 3.14159265358979323846)
    return {{0, 1, 2}, {0, 2, 3}};
  if (pts.size() == 4 && cross2(pts[1], pts[2], pts[3]) > 0 && cross2(pts[3], pts[0], pts[1]) > 0)
    return {{1, 2, 3}, {1, 3, 0}};
  while (ring.size() > 3) {
    const size_t n = ring.size(), i = nextEar(pts, ring);
    out.push_back({ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]});
    ring.erase(ring.begin() + long(i));
  }
  if (ring.size() == 3) out.push_back({ring[0], ring[1], ring[2]});
  return out;
}

bool insideRing(const std::vector<glm::dvec2>& ring, const glm::dvec2& p) {
  bool inside = false;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const glm::dvec2 &a = ring[i], &b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

/// What the hole filter needs: the triangles of geometry 1 and their scene.
struct HoleFilterData {
  const TraceScene* scene = nullptr;
  std::vector<int> triangles;  // primitive → triangle
};

/// Rejects hits that fall in a hole of the triangle's polygon.
void holeFilter(const RTCFilterFunctionNArguments* args) {
  const auto* data = static_cast<const HoleFilterData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const int t = data->triangles[RTCHitN_primID(args->hit, args->N, i)];
    const TraceTriangle& tri = data->scene->triangles()[size_t(t)];
    const double u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (data->scene->inHole(t, (1 - u - v) * tri.a + u * tri.b + v * tri.c)) args->valid[i] = 0;
  }
}

/// An Embree triangle geometry of triangles[global[i]], three vertices of its own each.
RTCGeometry triangleGeometry(RTCDevice device, const std::vector<TraceTriangle>& triangles,
                             const std::vector<int>& global) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n = global.size();
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                         RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                            RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (size_t i = 0; i < n; ++i) {
    const TraceTriangle& tri = triangles[size_t(global[i])];
    const glm::dvec3* corners[3] = {&tri.a, &tri.b, &tri.c};
    for (int k = 0; k < 3; ++k) {
      for (int d = 0; d < 3; ++d) vb[9 * i + 3 * size_t(k) + size_t(d)] = float((*corners[k])[d]);
      ib[3 * i + size_t(k)] = unsigned(3 * i + size_t(k));
    }
  }
  return geometry;
}

RTCRay makeRay(const glm::dvec3& o, const glm::dvec3& d, double tFar) {
  RTCRay r;
  r.org_x = float(o.x), r.org_y = float(o.y), r.org_z = float(o.z);
  r.dir_x = float(d.x), r.dir_y = float(d.y), r.dir_z = float(d.z);
  r.tnear = 0.f;
  r.tfar = float(tFar);
  r.time = 0.f;
  r.mask = ~0u;
  r.id = 0;
  r.flags = 0;
  return r;
}

}  // namespace

/// Embree's scene: geometry 0 holds the triangles without holes, geometry 1 those of polygons
/// with holes, whose hits in a hole a filter rejects.
struct TraceScene::Rays {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<int> plain;  // geometry 0: primitive → triangle
  HoleFilterData holed;    // geometry 1
  ~Rays() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

TraceScene::TraceScene(const Scene& scene) : scene_(scene) {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const auto& s : scene.surfaces)
    for (const auto& p : s.polygons)
      for (const auto& q : p.outer) lo = glm::min(lo, q), hi = glm::max(hi, q);
  centre_ = (lo + hi) * 0.5;
  size_ = std::max(glm::length(hi - lo), 1e-300);
  for (size_t s = 0; s < scene.surfaces.size(); ++s)
    for (const auto& polygon : scene.surfaces[s].polygons) addPolygon(polygon, int(s));
  // The emitters, by power.
  double total = 0;
  for (size_t t = 0; t < triangles_.size(); ++t) {
    const glm::dvec3 E = material(triangles_[t].surface).emission;
    const double power = (E.x + E.y + E.z) * triangles_[t].area * (twoSided(triangles_[t].surface) ? 2 : 1);
    if (!(power > 0)) continue;
    total += power;
    lightTriangle_.push_back(int(t));
    lightCdf_.push_back(total);
  }
  for (double& c : lightCdf_) c /= total;
  lightPdf_.assign(triangles_.size(), 0.0);
  for (size_t i = 0; i < lightTriangle_.size(); ++i) {
    const int t = lightTriangle_[i];
    lightPdf_[size_t(t)] = (lightCdf_[i] - (i ? lightCdf_[i - 1] : 0.0)) / triangles_[size_t(t)].area;
  }
  buildRays();
}

TraceScene::~TraceScene() = default;

const Material& TraceScene::material(int surface) const {
  return scene_.materials[size_t(scene_.surfaces[size_t(surface)].material)];
}

void TraceScene::addPolygon(const Polygon& polygon, int surface) {
  std::vector<glm::dvec3> ring;
  for (const auto& q : polygon.outer)
    if (ring.empty() || toLocal(q) != ring.back()) ring.push_back(toLocal(q));
  while (ring.size() > 1 && ring.back() == ring.front()) ring.pop_back();
  const glm::dvec3 newell = newellNormal(ring);
  if (ring.size() < 3 || !(glm::length(newell) > 0)) return;  // no area: nothing to hit
  const glm::dvec3 n = glm::normalize(newell);
  const glm::dvec3 u = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 v = glm::cross(n, u);
  std::vector<glm::dvec2> flat;
  for (const auto& p : ring) flat.push_back({glm::dot(p - ring[0], u), glm::dot(p - ring[0], v)});
  const int holes = polygon.holes.empty() ? -1 : addHoles(polygon, ring[0], u, v);
  for (const auto& t : earClip(flat)) {
    TraceTriangle tri{ring[size_t(t[0])], ring[size_t(t[1])], ring[size_t(t[2])], glm::dvec3(0.0), 0, surface, holes};
    const glm::dvec3 c = glm::cross(tri.b - tri.a, tri.c - tri.a);
    tri.area = 0.5 * glm::length(c);
    if (!(tri.area > 0)) continue;
    tri.normal = c / (2 * tri.area);
    triangles_.push_back(tri);
  }
}

int TraceScene::addHoles(const Polygon& polygon, const glm::dvec3& origin, const glm::dvec3& u,
                         const glm::dvec3& v) {
  HoleSet set{origin, u, v, {}};
  for (const auto& hole : polygon.holes) {
    std::vector<glm::dvec2> h;
    for (const auto& q : hole) h.push_back({glm::dot(toLocal(q) - origin, u), glm::dot(toLocal(q) - origin, v)});
    set.rings.push_back(std::move(h));
  }
  holes_.push_back(std::move(set));
  return int(holes_.size()) - 1;
}

void TraceScene::buildRays() {
  rays_ = std::make_unique<Rays>();
  Rays& r = *rays_;
  r.holed.scene = this;
  r.device = rtcNewDevice(nullptr);
  if (!r.device) throw std::runtime_error("embree: no device");
  r.scene = rtcNewScene(r.device);
  rtcSetSceneFlags(r.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(r.scene, RTC_BUILD_QUALITY_HIGH);
  for (size_t t = 0; t < triangles_.size(); ++t)
    (triangles_[t].holes >= 0 ? r.holed.triangles : r.plain).push_back(int(t));
  for (unsigned g = 0; g < 2; ++g) {
    const std::vector<int>& global = g ? r.holed.triangles : r.plain;
    if (global.empty()) continue;  // Embree takes no empty buffers
    RTCGeometry geometry = triangleGeometry(r.device, triangles_, global);
    if (g == 1) {
      rtcSetGeometryUserData(geometry, &r.holed);
      rtcSetGeometryIntersectFilterFunction(geometry, holeFilter);
      rtcSetGeometryOccludedFilterFunction(geometry, holeFilter);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(r.scene, geometry, g);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(r.scene);
  if (rtcGetDeviceError(r.device) != RTC_ERROR_NONE) throw std::runtime_error("embree: scene build failed");
}

TraceHit TraceScene::intersect(const glm::dvec3& origin, const glm::dvec3& direction, double tFar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = makeRay(origin, direction, tFar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(rays_->scene, &context, &rh);
  TraceHit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.triangle = (rh.hit.geomID ? rays_->holed.triangles : rays_->plain)[rh.hit.primID];
  const TraceTriangle& t = triangles_[size_t(hit.triangle)];
  // The point from the triangle's own corners in double precision: exactly on its plane.
  hit.point = (1.0 - rh.hit.u - rh.hit.v) * t.a + double(rh.hit.u) * t.b + double(rh.hit.v) * t.c;
  hit.front = glm::dot(t.normal, direction) < 0;
  return hit;
}

bool TraceScene::occluded(const glm::dvec3& from, const glm::dvec3& to) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = makeRay(from, to - from, 1.0);
  rtcOccluded1(rays_->scene, &context, &ray);
  return ray.tfar < 0;  // Embree marks an occluded ray with tfar = −∞
}

bool TraceScene::inHole(int t, const glm::dvec3& p) const {
  const int h = triangles_[size_t(t)].holes;
  if (h < 0) return false;
  const HoleSet& set = holes_[size_t(h)];
  const glm::dvec2 q(glm::dot(p - set.origin, set.u), glm::dot(p - set.origin, set.v));
  for (const auto& ring : set.rings)
    if (insideRing(ring, q)) return true;
  return false;
}

glm::dvec3 TraceScene::pointOn(int t, double u0, double u1) const {
  const TraceTriangle& tri = triangles_[size_t(t)];
  const double s = std::sqrt(u0);
  return (1 - s) * tri.a + (u1 * s) * tri.b + ((1 - u1) * s) * tri.c;
}

LightSample TraceScene::sampleLight(double u0, double u1, double u2) const {
  const size_t k = size_t(std::upper_bound(lightCdf_.begin(), lightCdf_.end(), u0) - lightCdf_.begin());
  const size_t i = std::min(k, lightCdf_.size() - 1);
  const int t = lightTriangle_[i];
  const TraceTriangle& tri = triangles_[size_t(t)];
  LightSample s;
  s.point = pointOn(t, u1, u2);
  s.normal = tri.normal;
  s.twoSided = twoSided(tri.surface);
  s.pdf = lightPdf_[size_t(t)];
  s.emission = inHole(t, s.point) ? glm::dvec3(0.0) : material(tri.surface).emission;
  return s;
}

}  // namespace rad::pathtrace
