#include "radiosity/pathtrace/trace_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "radiosity/pathtrace/ear_clip.h"
#include "radiosity/pathtrace/tangent_frame.h"

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

/// The coordinates of p in the plane frame (origin, u, v).
glm::dvec2 planeCoords(const glm::dvec3& p, const glm::dvec3& origin, const glm::dvec3& u, const glm::dvec3& v) {
  return {glm::dot(p - origin, u), glm::dot(p - origin, v)};
}

/// Whether p lies inside the ring (even-odd rule).
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

/// Whether hit i of the filter's packet lies in a hole of its triangle's polygon.
bool hitInHole(const RTCFilterFunctionNArguments* args, unsigned i) {
  const auto* data = static_cast<const HoleFilterData*>(args->geometryUserPtr);
  const int t = data->triangles[RTCHitN_primID(args->hit, args->N, i)];
  const TraceTriangle& tri = data->scene->triangle(t);
  const double u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
  return data->scene->inHole(t, (1 - u - v) * tri.a + u * tri.b + v * tri.c);
}

/// Rejects hits that fall in a hole of the triangle's polygon.
void holeFilter(const RTCFilterFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] == -1 && hitInHole(args, i)) args->valid[i] = 0;
}

/// Writes triangle i's three vertices of its own (single precision) and their indices.
void writeTriangle(const TraceTriangle& tri, size_t i, float* vb, unsigned* ib) {
  const glm::dvec3* corners[3] = {&tri.a, &tri.b, &tri.c};
  for (int k = 0; k < 3; ++k) {
    for (int d = 0; d < 3; ++d) vb[9 * i + 3 * size_t(k) + size_t(d)] = float((*corners[k])[d]);
    ib[3 * i + size_t(k)] = unsigned(3 * i + size_t(k));
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
  for (size_t i = 0; i < n; ++i) writeTriangle(triangles[size_t(global[i])], i, vb, ib);
  return geometry;
}

/// A single-precision Embree ray from o along d up to tFar.
RTCRay makeRay(const glm::dvec3& o, const glm::dvec3& d, double tFar) {
  // origin, tnear, direction, time, tfar, mask, id, flags
  return {float(o.x), float(o.y), float(o.z), 0.f, float(d.x), float(d.y), float(d.z), 0.f, float(tFar), ~0u, 0, 0};
}

/// Installs the hole filter on a geometry of triangles from polygons with holes.
void addHoleFilter(RTCGeometry geometry, HoleFilterData& data) {
  rtcSetGeometryUserData(geometry, &data);
  rtcSetGeometryIntersectFilterFunction(geometry, holeFilter);
  rtcSetGeometryOccludedFilterFunction(geometry, holeFilter);
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
  fitBox();
  for (size_t s = 0; s < scene.surfaces.size(); ++s)
    for (const auto& polygon : scene.surfaces[s].polygons) addPolygon(polygon, int(s));
  orderCoplanar();
  buildLights();
  buildRays();
}

TraceScene::~TraceScene() = default;

const Material& TraceScene::material(int surface) const {
  return scene_.materials[size_t(scene_.surfaces[size_t(surface)].material)];
}

void TraceScene::fitBox() {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const auto& s : scene_.surfaces)
    for (const auto& p : s.polygons)
      for (const auto& q : p.outer) lo = glm::min(lo, q), hi = glm::max(hi, q);
  centre_ = (lo + hi) * 0.5;
  size_ = std::max(glm::length(hi - lo), 1e-300);
}

double TraceScene::emittedPower(size_t t) const {
  const glm::dvec3 E = material(triangles_[t].surface).emission;
  return (E.x + E.y + E.z) * triangles_[t].area * (twoSided(triangles_[t].surface) ? 2 : 1);
}

void TraceScene::buildLights() {
  // The emitters, by power.
  double total = 0;
  for (size_t t = 0; t < triangles_.size(); ++t) {
    const double power = emittedPower(t);
    if (!(power > 0)) continue;
    total += power;
    lightTriangle_.push_back(int(t));
    lightCdf_.push_back(total);
  }
  for (double& c : lightCdf_) c /= total;
  fillLightPdf();
}

void TraceScene::fillLightPdf() {
  lightPdf_.assign(triangles_.size(), 0.0);
  for (size_t i = 0; i < lightTriangle_.size(); ++i) {
    const int t = lightTriangle_[i];
    lightPdf_[size_t(t)] = (lightCdf_[i] - (i ? lightCdf_[i - 1] : 0.0)) / triangles_[size_t(t)].area;
  }
}

std::vector<glm::dvec3> TraceScene::localRing(const Ring& outer) const {
  std::vector<glm::dvec3> ring;
  for (const auto& q : outer)
    if (ring.empty() || toLocal(q) != ring.back()) ring.push_back(toLocal(q));
  while (ring.size() > 1 && ring.back() == ring.front()) ring.pop_back();
  return ring;
}

void TraceScene::addPolygon(const Polygon& polygon, int surface) {
  const std::vector<glm::dvec3> ring = localRing(polygon.outer);
  const glm::dvec3 newell = newellNormal(ring);
  if (ring.size() < 3 || !(glm::length(newell) > 0)) return;  // no area: nothing to hit
  const auto [u, v] = tangentFrame(glm::normalize(newell));
  std::vector<glm::dvec2> flat;
  for (const auto& p : ring) flat.push_back(planeCoords(p, ring[0], u, v));
  const int holes = polygon.holes.empty() ? -1 : addHoles(polygon, ring[0], u, v);
  for (const auto& t : earClip(flat))
    addTriangle({ring[size_t(t[0])], ring[size_t(t[1])], ring[size_t(t[2])], glm::dvec3(0.0), 0, surface, holes});
}

void TraceScene::addTriangle(TraceTriangle tri) {
  const glm::dvec3 c = glm::cross(tri.b - tri.a, tri.c - tri.a);
  tri.area = 0.5 * glm::length(c);
  if (!(tri.area > 0)) return;
  tri.normal = c / (2 * tri.area);
  triangles_.push_back(tri);
}

void TraceScene::orderCoplanar() {
  // Triangles by plane: the normal to 1e-5, the offset in cells of 1e-5 of the scene's size
  // (the mesher's contact tolerance), a plane's neighbouring cells looked at too.
  using Key = std::array<long long, 4>;
  auto keyOf = [](const TraceTriangle& t, long long cell) {
    return Key{std::llround(t.normal.x * 1e5), std::llround(t.normal.y * 1e5), std::llround(t.normal.z * 1e5), cell};
  };
  auto cellOf = [](const TraceTriangle& t) { return std::llround(glm::dot(t.normal, t.a) * 1e5); };
  struct Extent {
    glm::dvec3 lo{HUGE_VAL}, hi{-HUGE_VAL};
  };
  std::map<Key, std::map<int, Extent>> inPlane;  // plane → its surfaces, each with its box there
  for (const TraceTriangle& t : triangles_) {
    Extent& e = inPlane[keyOf(t, cellOf(t))][t.surface];
    e.lo = glm::min(e.lo, glm::min(t.a, glm::min(t.b, t.c)));
    e.hi = glm::max(e.hi, glm::max(t.a, glm::max(t.b, t.c)));
  }
  std::vector<double> area(scene_.surfaces.size(), 0.0);
  // Each surface's area as its polygons give it: outlines less holes, however they wind.
  for (size_t s = 0; s < scene_.surfaces.size(); ++s)
    for (const Polygon& p : scene_.surfaces[s].polygons) {
      area[s] += 0.5 * glm::length(newellNormal(p.outer));
      for (const Ring& hole : p.holes) area[s] -= 0.5 * glm::length(newellNormal(hole));
    }
  // Front first: smaller area, then later in the file.
  auto inFront = [&](int a, int b) { return area[size_t(a)] != area[size_t(b)] ? area[size_t(a)] < area[size_t(b)] : a > b; };
  auto meet = [](const Extent& x, const Extent& y) {
    return glm::all(glm::lessThanEqual(x.lo, y.hi + kRayOffset)) && glm::all(glm::lessThanEqual(y.lo, x.hi + kRayOffset));
  };
  for (TraceTriangle& t : triangles_) {
    const long long cell = cellOf(t);
    const Extent& own = inPlane[keyOf(t, cell)][t.surface];
    std::set<int> before;  // surfaces in its plane, in front of it, whose boxes there meet its own
    for (long long c = cell - 1; c <= cell + 1; ++c) {
      auto it = inPlane.find(keyOf(t, c));
      if (it == inPlane.end()) continue;
      for (const auto& [s, extent] : it->second)
        if (s != t.surface && inFront(s, t.surface) && meet(own, extent)) before.insert(s);
    }
    const glm::dvec3 back = -double(std::min<size_t>(before.size(), kMaxCoplanarSteps)) * kCoplanarStep * t.normal;
    t.a += back, t.b += back, t.c += back;
  }
}

int TraceScene::addHoles(const Polygon& polygon, const glm::dvec3& origin, const glm::dvec3& u,
                         const glm::dvec3& v) {
  HoleSet set{origin, u, v, {}};
  for (const auto& hole : polygon.holes) {
    std::vector<glm::dvec2> h;
    for (const auto& q : hole) h.push_back(planeCoords(toLocal(q), origin, u, v));
    set.rings.push_back(std::move(h));
  }
  holes_.push_back(std::move(set));
  return int(holes_.size()) - 1;
}

void TraceScene::newRays() {
  rays_ = std::make_unique<Rays>();
  Rays& r = *rays_;
  r.holed.scene = this;
  r.device = rtcNewDevice(nullptr);
  if (!r.device) throw std::runtime_error("embree: no device");
  r.scene = rtcNewScene(r.device);
  rtcSetSceneFlags(r.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(r.scene, RTC_BUILD_QUALITY_HIGH);
}

void TraceScene::buildRays() {
  newRays();
  Rays& r = *rays_;
  for (size_t t = 0; t < triangles_.size(); ++t)
    (triangles_[t].holes >= 0 ? r.holed.triangles : r.plain).push_back(int(t));
  attachGeometry(0, r.plain);
  attachGeometry(1, r.holed.triangles);
  rtcCommitScene(r.scene);
  if (rtcGetDeviceError(r.device) != RTC_ERROR_NONE) throw std::runtime_error("embree: scene build failed");
}

void TraceScene::attachGeometry(unsigned id, const std::vector<int>& global) {
  if (global.empty()) return;  // Embree takes no empty buffers
  RTCGeometry geometry = triangleGeometry(rays_->device, triangles_, global);
  if (id == 1) addHoleFilter(geometry, rays_->holed);
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(rays_->scene, geometry, id);
  rtcReleaseGeometry(geometry);
}

TraceHit TraceScene::intersect(const glm::dvec3& origin, const glm::dvec3& direction, double tFar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = makeRay(origin, direction, tFar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(rays_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return TraceHit{};
  const int triangle = (rh.hit.geomID ? rays_->holed.triangles : rays_->plain)[rh.hit.primID];
  return hitOn(triangle, rh.hit.u, rh.hit.v, direction);
}

TraceHit TraceScene::hitOn(int triangle, float u, float v, const glm::dvec3& direction) const {
  TraceHit hit;
  hit.triangle = triangle;
  const TraceTriangle& t = triangles_[size_t(triangle)];
  // The point from the triangle's own corners in double precision: exactly on its plane.
  hit.point = (1.0 - u - v) * t.a + double(u) * t.b + double(v) * t.c;
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
  const glm::dvec2 q = planeCoords(p, set.origin, set.u, set.v);
  return std::any_of(set.rings.begin(), set.rings.end(), [&](const auto& ring) { return insideRing(ring, q); });
}

glm::dvec3 TraceScene::pointOn(int t, double u0, double u1) const {
  const TraceTriangle& tri = triangles_[size_t(t)];
  const double s = std::sqrt(u0);
  return (1 - s) * tri.a + (u1 * s) * tri.b + ((1 - u1) * s) * tri.c;
}

int TraceScene::lightTriangle(double u) const {
  const size_t k = size_t(std::upper_bound(lightCdf_.begin(), lightCdf_.end(), u) - lightCdf_.begin());
  return lightTriangle_[std::min(k, lightCdf_.size() - 1)];
}

LightSample TraceScene::sampleLight(double u0, double u1, double u2) const {
  const int t = lightTriangle(u0);
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
