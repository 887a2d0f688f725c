#include "radiosity/light/direct_light.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include "mesh/base/color.h"
#include "mesh/base/error.h"
#include "mesh/scene/geometry.h"
#include "mesh/base/parallel.h"
#include "mesh/base/progress.h"
#include "radiosity/light/clear_sight.h"
#include "radiosity/formfactors/element_hierarchy.h"
#include "radiosity/formfactors/point_polygon.h"
#include "radiosity/shooting/shooter_samples.h"

namespace rad {
namespace {

/// The outline of a patch (PatchMesh::boundaryLoops) as points. Lambert's contour sum over
/// the loops is the patch's, pinched or not, as it is a sum over the boundary's edges.
std::vector<std::vector<glm::dvec3>> patchLoops(const PatchMesh& mesh, const Patch& patch) {
  const int id = mesh.patch(patch.elements[0]);
  std::vector<std::vector<glm::dvec3>> loops;
  for (const auto& loop : mesh.boundaryLoops(patch.elements, [&](int e) { return mesh.patch(e) == id; })) {
    std::vector<glm::dvec3>& points = loops.emplace_back();
    for (int v : loop) points.push_back(PatchMesh::toGlm(mesh.mesh.point(TriMesh::VertexHandle(v))));
  }
  return loops;
}

/// Ray ends are moved this far (relative to the scene size) off their surfaces: off the
/// receiver along its normal and towards its own elements (a vertex at the foot of a wall
/// must not start its rays inside the wall's plane), and off the emitter along its normal.
constexpr double kRayOffset = 1e-5;
/// Near small elements the receiver's offset shrinks to this share of their size, but not
/// below kMinRayOffset of the scene size (single-precision rays in coordinates normalised to
/// the scene: about 17 units in the last place).
constexpr double kRayOffsetOfElement = 1e-3;
constexpr double kMinRayOffset = 1e-6;
/// An element closer than this (relative to the scene size) to the space between a point and
/// a light may block a single-precision ray (rounding of origin, direction and corners in
/// coordinates normalised to the scene): the light is not taken to be clear. Below
/// kMinRayOffset, so that the surface a point lies on stays apart.
constexpr double kClearSightMargin = 3e-7;
/// A probe's inwards shorter than this (relative to the scene size) is rounding, no direction.
constexpr double kNoDirection = 1e-9;
/// A point between two ends that see different samples tests every this many-th of the
/// samples both ends see (and every sample they agree on, should one of those be hidden).
/// Only those: a convex occluder's shadow (from a sample) can hold the point between two ends
/// outside it, but not leave it out between two ends inside it. Measured (the Cornell box's
/// edges, tests/direct_light_test.cpp): every 12th of those both see, against every 8th of all
/// they agree on, half the checking rays and a smaller worst point (3.7 against 4.2 %); every
/// 16th of all let through a point twice as wrong.
constexpr size_t kAgreementCheck = 12;

/// The emitting patches, and per surface side (surface·2 + side) their area.
std::vector<int> emittingPatches(const PatchMesh& mesh, std::vector<double>& sideArea) {
  std::vector<int> emitters;
  sideArea.assign(mesh.surfaces.size() * 2, 0.0);
  for (int p = 0; p < int(mesh.patches.size()); ++p) {
    if (!mesh.emits(p)) continue;
    emitters.push_back(p);
    sideArea[size_t(mesh.patches[p].surface * 2 + mesh.patches[p].side)] += mesh.patches[p].area;
  }
  return emitters;
}

}  // namespace

/// Embree's device and scene: every element, in coordinates (p − centre)/size so that single
/// precision holds at any scene scale.
struct DirectLight::Rays {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  glm::dvec3 centre{0.0};
  double scale = 1;

  ~Rays() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  /// centre and scale: the mesh's bounding box.
  void frame(const PatchMesh& mesh);
  /// Embree's scene of every element of the mesh, normalised to its bounding box.
  void build(const PatchMesh& mesh);

  /// The segment from a to b (scene coordinates) as Embree's ray, normalised.
  RTCRay segment(const glm::dvec3& a, const glm::dvec3& b) const {
    const glm::dvec3 o = (a - centre) / scale, d = (b - a) / scale;
    RTCRay ray{};
    ray.org_x = float(o.x), ray.org_y = float(o.y), ray.org_z = float(o.z);
    ray.dir_x = float(d.x), ray.dir_y = float(d.y), ray.dir_z = float(d.z);
    ray.tnear = 0.0f;
    ray.tfar = 1.0f;
    ray.mask = 0xFFFFFFFFu;
    return ray;
  }

  /// Rays per packet: the widest Embree traverses natively on this processor (8 with AVX2,
  /// where 16 are taken as two 8s and cost a sixth more in all).
  int packet = 4;

  /// Whether each segment from a to a point of `to` is blocked, in packets of rays from one
  /// origin (coherent: Embree traverses each packet together).
  void blocked(const glm::dvec3& a, const std::vector<glm::dvec3>& to, std::vector<char>& out) const {
    out.assign(to.size(), 0);
    if (packet == 16)
      blockedIn<RTCRay16, 16>(a, to, out, rtcOccluded16);
    else if (packet == 8)
      blockedIn<RTCRay8, 8>(a, to, out, rtcOccluded8);
    else
      blockedIn<RTCRay4, 4>(a, to, out, rtcOccluded4);
  }

  template <class Packet, size_t N, class Occluded>
  void blockedIn(const glm::dvec3& a, const std::vector<glm::dvec3>& to, std::vector<char>& out,
                 Occluded occluded) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (size_t first = 0; first < to.size(); first += N) {
      const size_t count = std::min(N, to.size() - first);
      alignas(64) Packet rays;
      alignas(64) int valid[N];
      for (size_t k = 0; k < N; ++k) {
        const RTCRay ray = segment(a, to[first + std::min(k, count - 1)]);
        valid[k] = k < count ? -1 : 0;
        rays.org_x[k] = ray.org_x, rays.org_y[k] = ray.org_y, rays.org_z[k] = ray.org_z;
        rays.dir_x[k] = ray.dir_x, rays.dir_y[k] = ray.dir_y, rays.dir_z[k] = ray.dir_z;
        rays.tnear[k] = ray.tnear, rays.tfar[k] = ray.tfar, rays.mask[k] = ray.mask;
        rays.time[k] = 0.0f, rays.id[k] = 0, rays.flags[k] = 0;
      }
      occluded(valid, scene, &context, &rays);
      for (size_t k = 0; k < count; ++k) out[first + k] = rays.tfar[k] < 0;
    }
  }
};

void DirectLight::Rays::frame(const PatchMesh& mesh) {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (auto v : mesh.mesh.vertices()) {
    const glm::dvec3 p = PatchMesh::toGlm(mesh.mesh.point(v));
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  centre = (lo + hi) * 0.5;
  scale = std::max(glm::length(hi - lo), 1e-300);
}

void DirectLight::Rays::build(const PatchMesh& mesh) {
  frame(mesh);
  device = rtcNewDevice("threads=1");
  if (!device) throw std::runtime_error("embree: no device");
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED))
    packet = 16;
  else if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED))
    packet = 8;
  scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                         3 * sizeof(float), mesh.mesh.n_vertices()));
  for (auto v : mesh.mesh.vertices()) {
    const glm::dvec3 p = (PatchMesh::toGlm(mesh.mesh.point(v)) - centre) / scale;
    for (int k = 0; k < 3; ++k) vb[3 * v.idx() + k] = float(p[k]);
  }
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                            3 * sizeof(unsigned), mesh.mesh.n_faces()));
  for (auto f : mesh.mesh.faces()) {
    int k = 0;
    for (auto v : mesh.mesh.fv_range(f)) ib[3 * f.idx() + k++] = unsigned(v.idx());
  }
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("embree: scene build failed");
}

double mostEmittingPatches(const Scene& scene, double elementEdge) {
  const double elementArea = kLeastElementArea * elementEdge * elementEdge;
  double patches = 0;
  for (const Surface& s : scene.surfaces) {
    if (!scene.materials[s.material].emits()) continue;
    const double sides = s.twoSided ? 2 : 1;
    for (const Polygon& p : s.polygons) patches += sides * std::max(1.0, polygonArea(p) / elementArea);
  }
  return patches;
}

DirectLight::DirectLight(const PatchMesh& mesh, double sceneSize, int samplesPerEmitter, int raysPerPoint,
                         int workers)
    : rays_impl_(std::make_unique<Rays>()), sceneSize_(sceneSize), raysPerPoint_(raysPerPoint),
      workers_(workerCount(workers)) {
  // The lights: every emitting patch, with samples by its share of its surface side.
  std::vector<double> sideArea;
  const std::vector<int> emitters = emittingPatches(mesh, sideArea);
  enabled_ = !emitters.empty() && int(emitters.size()) <= kMaxRayEmitterPatches;
  if (!enabled_) return;
  // Many glowing surfaces share one budget of samples (rays per vertex).
  const int sides = int(std::count_if(sideArea.begin(), sideArea.end(), [](double a) { return a > 0; }));
  samplesPerEmitter = std::max(1, std::min(samplesPerEmitter, kMaxLightSamples / sides));
  for (int p : emitters) {
    const Patch& patch = mesh.patches[p];
    const double share = patch.area / sideArea[size_t(patch.surface * 2 + patch.side)];
    addLight(mesh, p, std::max(1, int(std::lround(samplesPerEmitter * share))));
  }
  samples_ = int(points_.size());
  // The occluders: every element, for the rays and for the clear-sight test.
  rays_impl_->build(mesh);
  std::vector<glm::dvec3> positions, normals;
  std::vector<uint32_t> indices;
  for (auto v : mesh.mesh.vertices()) positions.push_back(PatchMesh::toGlm(mesh.mesh.point(v)));
  for (auto f : mesh.mesh.faces()) {
    for (auto v : mesh.mesh.fv_range(f)) indices.push_back(uint32_t(v.idx()));
    // Each triangle's own plane (a piece's plane is a best fit, its corners within kPlanarity
    // of it): the clear-sight test separates by it.
    const size_t i = indices.size() - 3;
    const glm::dvec3 a = positions[indices[i]];
    const glm::dvec3 n = glm::cross(positions[indices[i + 1]] - a, positions[indices[i + 2]] - a);
    normals.push_back(glm::length(n) > 0 ? glm::normalize(n) : PatchMesh::toGlm(mesh.mesh.normal(f)));
  }
  occluders_ = std::make_unique<ElementHierarchy>(positions, indices, normals);
  clearSight_ = std::make_unique<ClearSight>(*occluders_, kClearSightMargin * sceneSize_);
}

void DirectLight::addSample(const glm::dvec3& at, const glm::dvec3& normal) {
  onLight_.push_back(at);
  for (int a = 0; a < 3; ++a) onLightAxes_[size_t(a)].push_back(at[a]);
  points_.push_back(at + normal * (kRayOffset * sceneSize_));
}

void DirectLight::addLight(const PatchMesh& mesh, int p, int count) {
  const Patch& patch = mesh.patches[p];
  LightPolygon light;
  light.normal = patch.normal;
  light.emission = mesh.emission(patch.elements[0]);
  light.first = int(points_.size());
  // Strata of equal area, neighbours in order, over the whole patch (a ring round its hole
  // too): a tested sample stands for the stride of them after it.
  for (const ShooterSample& s : patchSamples(mesh, p, count)) addSample(s.point, light.normal);
  light.count = int(points_.size()) - light.first;
  light.outlines = patchLoops(mesh, patch);
  if (light.outlines.empty())  // no closed loops: the elements' outlines
    for (int e : patch.elements) {
      const auto c = mesh.corners(e);
      light.outlines.emplace_back(c.begin(), c.end());
    }
  std::vector<glm::dvec3> corners;
  for (const auto& o : light.outlines) corners.insert(corners.end(), o.begin(), o.end());
  const PlaneFrame frame = planeFrame(corners[0], light.normal);
  std::vector<glm::dvec2> projected;
  for (const glm::dvec3& c : corners) projected.push_back(frame.project(c));
  for (size_t k : convexHull(projected)) light.hull.push_back(corners[k]);
  light.rayHull = light.hull;
  light.size = ringDiameter(light.hull);
  // The pyramid's base halfway between the emitter and the ray ends: it holds every ray
  // whole, and the emitter's own elements stay well outside it.
  for (glm::dvec3& corner : light.rayHull) corner += light.normal * (0.5 * kRayOffset * sceneSize_);
  lights_.push_back(std::move(light));
}

DirectLight::~DirectLight() = default;

DirectLight::Probe vertexProbe(const PatchMesh& mesh, TriMesh::VertexHandle v) {
  DirectLight::Probe probe;
  probe.point = PatchMesh::toGlm(mesh.mesh.point(v));
  probe.normal = PatchMesh::toGlm(mesh.mesh.normal(v));
  int faces = 0;
  for (auto f : mesh.mesh.vf_range(v)) {
    if (faces++ == 0) probe.rho = mesh.reflectance(f.idx());
    probe.inwards += mesh.centroid(f.idx());
  }
  for (auto w : mesh.mesh.vv_range(v)) {
    const double edge = (mesh.mesh.point(w) - mesh.mesh.point(v)).norm();
    probe.size = probe.size > 0 ? std::min(probe.size, edge) : edge;
  }
  if (faces) probe.inwards = probe.inwards / double(faces) - probe.point;
  return probe;
}

glm::dvec3 offSurface(const DirectLight::Probe& probe, double sceneSize) {
  double offset = kRayOffset * sceneSize;
  if (probe.size > 0)
    offset = std::clamp(kRayOffsetOfElement * probe.size, kMinRayOffset * sceneSize, offset);
  // Inwards along the surface only; a vertex amid its elements has their centroids all round
  // it, and what is left of their sum is rounding, no direction (along the normal it would
  // cancel the offset off the surface: the rays would start in it and see nothing).
  const glm::dvec3 along = probe.inwards - probe.normal * glm::dot(probe.inwards, probe.normal);
  const double inwards = glm::length(along);
  return probe.point + probe.normal * offset +
         (inwards > kNoDirection * sceneSize ? along * (offset / inwards) : glm::dvec3(0.0));
}

namespace {

/// The 64 bits of `bits` from bit j on (past its end: zeros).
uint64_t bitsFrom(const std::vector<uint64_t>& bits, size_t j) {
  const size_t word = j >> 6, shift = j & 63;
  const uint64_t low = bits[word] >> shift;
  return shift && word + 1 < bits.size() ? low | bits[word + 1] << (64 - shift) : low;
}

/// The bits of w as 0/1 chars at out[0, count), count ≤ 64, eight at a time (bit i of a byte
/// to byte i of a word, little-endian).
void unpackBits(uint64_t w, char* out, size_t count) {
  static const std::array<uint64_t, 256> bytes = [] {
    std::array<uint64_t, 256> t{};
    for (size_t b = 0; b < 256; ++b)
      for (size_t i = 0; i < 8; ++i) t[b] |= uint64_t(b >> i & 1) << (8 * i);
    return t;
  }();
  size_t k = 0;
  for (; k + 8 <= count; k += 8) std::memcpy(out + k, &bytes[(w >> k) & 255], 8);
  for (; k < count; ++k) out[k] = char(w >> k & 1);
}

/// Whether the (ascending) sample indices are consecutive: a light's run of samples, wholly
/// above a point's horizon, which its bit words and axis arrays hold in order.
bool isRun(const std::vector<int>& samples) {
  return !samples.empty() && size_t(samples.back() - samples.front()) + 1 == samples.size();
}

/// Sets bit samples[k] of `bits` where visible[k] (consecutive samples 64 at a time).
void setBits(const std::vector<int>& samples, const std::vector<char>& visible, std::vector<uint64_t>& bits) {
  const size_t n = samples.size();
  if (n == 0) return;
  if (!isRun(samples)) {
    for (size_t k = 0; k < n; ++k) bits[size_t(samples[k]) >> 6] |= uint64_t(visible[k]) << (size_t(samples[k]) & 63);
    return;
  }
  for (size_t k0 = 0; k0 < n; k0 += 64) {
    uint64_t w = 0;
    for (size_t k = k0; k < std::min(n, k0 + 64); ++k) w |= uint64_t(visible[k]) << (k - k0);
    const size_t j = size_t(samples[k0]), word = j >> 6, shift = j & 63;
    bits[word] |= w << shift;
    if (shift && w >> (64 - shift)) bits[word + 1] |= w >> (64 - shift);
  }
}

/// samplesVisible's lists, one set per thread.
struct SampleLists {
  std::vector<glm::dvec3> to;
  std::vector<size_t> at, differing;
  std::vector<char> blocked;
};

}  // namespace

void DirectLight::samplesVisible(const Probe& probe, const glm::dvec3& origin, const std::vector<int>& samples,
                                 std::vector<char>& visible, long& raysCast) const {
  const size_t n = samples.size();
  visible.resize(n);
  thread_local SampleLists lists;
  SampleLists& l = lists;
  // Casts the rays to samples[k] for k in `which`; how many found other than `visible` held.
  auto cast = [&](const std::vector<size_t>& which) {
    l.to.clear();
    for (size_t k : which) l.to.push_back(points_[size_t(samples[k])]);
    rays_impl_->blocked(origin, l.to, l.blocked);
    raysCast += long(l.to.size());
    size_t changed = 0;
    for (size_t i = 0; i < which.size(); ++i) {
      const char seen = !l.blocked[i];
      changed += seen != visible[which[i]];
      visible[which[i]] = seen;
    }
    return changed;
  };
  if (!probe.visible) {
    l.at.resize(n);
    for (size_t k = 0; k < n; ++k) l.at[k] = k;
    cast(l.at);
    return;
  }
  // Consecutive samples (a light wholly above the horizon) are read 64 at a time.
  const bool run = isRun(samples);
  const size_t first = run ? size_t(samples.front()) : 0;
  auto bit = [](const std::vector<uint64_t>& bits, int j) { return char(bits[size_t(j) >> 6] >> (size_t(j) & 63) & 1); };
  if (run)
    for (size_t k0 = 0; k0 < n; k0 += 64) unpackBits(bitsFrom(*probe.visible, first + k0), &visible[k0], std::min<size_t>(64, n - k0));
  else
    for (size_t k = 0; k < n; ++k) visible[k] = bit(*probe.visible, samples[k]);
  if (!probe.alsoVisible) return;
  // Between two ends that see different samples: rays to every kAgreementCheck-th of the
  // samples both see, and to those they do not agree on. A sample both ends see may still be
  // hidden from a point between them (past the corner of its shadow); should a checked one
  // be, every sample they agree on is tested.
  l.at.clear(), l.differing.clear();
  if (run) {
    size_t agreed = 0;  // before this word
    for (size_t k0 = 0; k0 < n; k0 += 64) {
      const uint64_t mask = n - k0 >= 64 ? ~uint64_t(0) : (uint64_t(1) << (n - k0)) - 1;
      const uint64_t differ = (bitsFrom(*probe.visible, first + k0) ^ bitsFrom(*probe.alsoVisible, first + k0)) & mask;
      for (uint64_t d = differ; d; d &= d - 1) l.differing.push_back(k0 + size_t(__builtin_ctzll(d)));
      // The samples both see of rank check, check + kAgreementCheck, ... in this word.
      uint64_t agree = ~differ & mask & bitsFrom(*probe.visible, first + k0);
      const size_t count = size_t(__builtin_popcountll(agree));
      size_t rank = agreed;  // of agree's lowest bit
      for (size_t check = (agreed + kAgreementCheck - 1) / kAgreementCheck * kAgreementCheck; check < agreed + count;
           check += kAgreementCheck) {
        for (; rank < check; ++rank) agree &= agree - 1;
        l.at.push_back(k0 + size_t(__builtin_ctzll(agree)));
      }
      agreed += count;
    }
  } else {
    size_t agreed = 0;
    for (size_t k = 0; k < n; ++k)
      if (bit(*probe.alsoVisible, samples[k]) != visible[k])
        l.differing.push_back(k);
      else if (visible[k] && agreed++ % kAgreementCheck == 0)
        l.at.push_back(k);
  }
  if (!l.at.empty() && cast(l.at) > 0) {  // contradicted: every other sample they agree on too
    size_t agreed = 0;
    for (size_t k = 0; k < n; ++k) {
      const char a = bit(*probe.visible, samples[k]), b = bit(*probe.alsoVisible, samples[k]);
      if (a == b && (!a || agreed++ % kAgreementCheck)) l.differing.push_back(k);
    }
  }
  if (!l.differing.empty()) cast(l.differing);
}

namespace {

/// The stride through a light's samples above a point's horizon (`above` of them) for the
/// light's `share` of the point's light: a power of two leaving at least raysPerPoint·share
/// samples, and never fewer than kMinRaysPerLight.
size_t sampleStride(size_t above, double share, int raysPerPoint) {
  const double wanted = std::max(double(kMinRaysPerLight), raysPerPoint * share);
  size_t stride = 1;
  while (double(above) / double(2 * stride) >= wanted) stride *= 2;
  return stride;
}

}  // namespace

/// One light as a point sees it: its samples above the point's horizon and which are visible.
/// Every stride-th sample is tested by a ray; consecutive samples are neighbouring strata
/// (patchSamples bisects by area), so each tested one stands for the stride of them from it.
/// A light seen partly counts each visible sample by its own differential factor
/// cosθ·cosθ'/r² (samples stand for equal areas, so that near a light its close parts count
/// more); those are weighed only then, as a light seen whole or not at all needs no weights.
struct DirectLight::SeenLight {
  std::vector<int> above;
  std::vector<char> visible;  ///< per sample above, tested or taken from the tested one before it
  std::vector<double> weight; ///< per sample above, once weighed
  double F = 0;               ///< the light's exact unoccluded factor
  double share = -1;          ///< the visible share of its weight, once found (-1: not yet)
  size_t stride = 0;          ///< 0: nothing tested yet

  /// Every sample visible, as if each were tested (nothing stands between point and light).
  void seeWhole() {
    visible.assign(above.size(), 1);
    stride = 1;
    share = -1;
  }
  /// How many samples are visible (tested, or taken from a tested one).
  size_t seen() const { return size_t(std::count(visible.begin(), visible.end(), char(1))); }
  /// Whether some tested samples are visible and some not (the point is in its penumbra).
  bool partial() const {
    const size_t n = seen();
    return n > 0 && n < visible.size();
  }
};

double DirectLight::unoccludedFactor(const glm::dvec3& p, const glm::dvec3& n, size_t t) const {
  const LightPolygon& light = lights_[t];
  if (glm::dot(light.normal, p - light.outlines[0][0]) <= 0) return 0;  // behind the emitter
  const double F = pointRegionFormFactor(p, n, light.outlines);
  return F > 0 ? F : 0;
}

namespace {

/// A light is taken to lie wholly above a point's horizon, and the point wholly in front of
/// it, when every corner of its hull is above by this share of its distance, plus
/// kPlanarSlack of the light's size, at least: then every sample is, whatever the rounding
/// (samples lie inside the hull but for a piece's planarity tolerance).
constexpr double kWhollyAbove = 1e-9;
constexpr double kPlanarSlack = 4 * kPlanarity;

}  // namespace

bool DirectLight::whollyAbove(const glm::dvec3& p, const glm::dvec3& n, size_t t) const {
  const LightPolygon& light = lights_[t];
  bool whole = true;
  for (const glm::dvec3& c : light.hull) {
    const glm::dvec3 d = c - p;
    const double margin = kWhollyAbove * glm::length(d) + kPlanarSlack * light.size;
    whole = whole && glm::dot(n, d) > margin && -glm::dot(light.normal, d) > margin;
  }
  return whole;
}

void DirectLight::samplesAbove(const glm::dvec3& p, const glm::dvec3& n, size_t t, SeenLight& out) const {
  out.above.clear(), out.weight.clear(), out.visible.clear();
  out.stride = 0, out.share = -1;
  const LightPolygon& light = lights_[t];
  out.F = unoccludedFactor(p, n, t);
  if (!(out.F > 0)) return;
  if (whollyAbove(p, n, t)) {
    out.above.resize(size_t(light.count));
    for (int k = 0; k < light.count; ++k) out.above[size_t(k)] = light.first + k;
  } else {
    for (int j = light.first; j < light.first + light.count; ++j) {
      const glm::dvec3 d = onLight_[size_t(j)] - p;
      // Below the horizon, or behind the light.
      if (glm::dot(n, d) <= 0 || -glm::dot(light.normal, d) <= 0) continue;
      out.above.push_back(j);
    }
  }
  out.visible.assign(out.above.size(), 0);
}

double DirectLight::seenShare(const glm::dvec3& p, const glm::dvec3& n, size_t t, SeenLight& light) const {
  if (light.share >= 0) return light.share;
  const size_t seen = light.seen();
  if (seen == light.visible.size()) return light.share = 1;  // the weighted sum over all, exactly
  if (seen == 0) return light.share = 0;
  if (light.weight.empty()) {
    const glm::dvec3& ln = lights_[t].normal;
    const size_t m = light.above.size();
    light.weight.resize(m);
    double* weight = light.weight.data();
    // Axis by axis over a run of samples (a light wholly above the horizon), in the order of
    // glm::dot's terms (the same weights as point by point while the compiler contracts no
    // multiply-add, as at the default x86-64 target), so that the loop is vectorised.
    if (isRun(light.above)) {
      const size_t first = size_t(light.above[0]);
      const double *x = onLightAxes_[0].data() + first, *y = onLightAxes_[1].data() + first,
                   *z = onLightAxes_[2].data() + first;
      for (size_t k = 0; k < m; ++k) {
        const double dx = x[k] - p.x, dy = y[k] - p.y, dz = z[k] - p.z;
        const double r2 = dx * dx + dy * dy + dz * dz, cosHere = n.x * dx + n.y * dy + n.z * dz;
        const double cosThere = -(ln.x * dx + ln.y * dy + ln.z * dz);
        weight[k] = cosHere * cosThere / (r2 * r2);
      }
    } else {
      for (size_t k = 0; k < m; ++k) {
        const glm::dvec3 d = onLight_[size_t(light.above[k])] - p;
        const double r2 = glm::dot(d, d), cosHere = glm::dot(n, d), cosThere = -glm::dot(ln, d);
        weight[k] = cosHere * cosThere / (r2 * r2);
      }
    }
  }
  double sum = 0, all = 0;
  for (size_t k = 0; k < light.above.size(); ++k) {
    all += light.weight[k];
    sum += light.weight[k] * double(light.visible[k]);
  }
  return light.share = all > 0 ? sum / all : 0.0;
}

void DirectLight::test(const Probe& probe, const glm::dvec3& p, size_t stride, SeenLight& light,
                       long& raysCast) const {
  if (light.stride && light.stride <= stride) return;
  if (!light.stride && stride == 1) {  // every sample, none tested yet: straight in
    samplesVisible(probe, p, light.above, light.visible, raysCast);
    light.stride = 1;
    light.share = -1;
    return;
  }
  thread_local std::vector<int> samples;
  thread_local std::vector<size_t> at;
  thread_local std::vector<char> visible;
  samples.clear(), at.clear();
  for (size_t k = 0; k < light.above.size(); k += stride)
    if (!light.stride || k % light.stride) samples.push_back(light.above[k]), at.push_back(k);
  samplesVisible(probe, p, samples, visible, raysCast);
  for (size_t i = 0; i < at.size(); ++i) light.visible[at[i]] = visible[i];
  light.stride = stride;
  light.share = -1;
  if (stride > 1)
    for (size_t k = 0; k < light.above.size(); ++k)
      if (k % stride) light.visible[k] = light.visible[k - k % stride];
}

namespace {

/// How many of the bits [first, first + count) of the words word(0), word(1), ... are set.
template <class Word>
size_t bitsSetIn(int first, int count, const Word& word) {
  size_t set = 0;
  for (int j = first; j < first + count;) {
    const int at = j / 64, from = j % 64, to = std::min(64, from + (first + count - j));
    uint64_t w = word(size_t(at)) >> from;
    if (to - from < 64) w &= (uint64_t(1) << (to - from)) - 1;
    set += size_t(__builtin_popcountll(w));
    j += to - from;
  }
  return set;
}

size_t bitsSet(const std::vector<uint64_t>& bits, int first, int count) {
  return bitsSetIn(first, count, [&](size_t w) { return bits[w]; });
}

/// How many of the bits [first, first + count) differ between a and b.
size_t bitsDiffer(const std::vector<uint64_t>& a, const std::vector<uint64_t>& b, int first, int count) {
  return bitsSetIn(first, count, [&](size_t w) { return a[w] ^ b[w]; });
}

}  // namespace

bool DirectLight::fromEnds(const Probe& probe, const glm::dvec3& p, VertexLight& out) const {
  struct Seen {
    double F;
    bool all;
  };
  thread_local std::vector<Seen> seen;
  seen.assign(lights_.size(), {0.0, false});
  for (size_t t = 0; t < lights_.size(); ++t) {
    const LightPolygon& light = lights_[t];
    // A penumbra is weighed sample by sample (compute): told first, before any factor.
    const size_t set = bitsSet(*probe.visible, light.first, light.count);
    if (set != 0 && set != size_t(light.count)) return false;
    const double F = unoccludedFactor(p, probe.normal, t);
    if (!(F > 0)) continue;
    if (!whollyAbove(p, probe.normal, t)) return false;  // some samples below the horizon
    seen[t] = {F, set != 0};
  }
  for (size_t t = 0; t < lights_.size(); ++t) {
    const LightPolygon& light = lights_[t];
    if (!(seen[t].F > 0)) continue;
    const glm::dvec3 full = probe.rho * light.emission * seen[t].F;
    if (seen[t].all) {
      out.radiosity += full;
      for (int j = light.first; j < light.first + light.count; ++j) out.visible[size_t(j) >> 6] |= uint64_t(1) << (j & 63);
    }
    out.weight[t] = float(luminance(full) / double(light.count));
  }
  return true;
}

VertexLight DirectLight::compute(const Probe& probe, long& raysCast, long& seenWhole) const {
  VertexLight out;
  out.visible.assign(size_t((samples_ + 63) / 64), 0);
  out.weight.assign(lights_.size(), 0.0f);
  if (probe.rho == glm::dvec3(0.0)) return out;  // black: nothing to show
  const glm::dvec3 p = offSurface(probe, sceneSize_), &n = probe.normal;
  // Between two ends that see the same samples, each light seen whole or not at all: its
  // light at once, as the samples would give it.
  if (probe.visible && !probe.alsoVisible && fromEnds(probe, p, out)) return out;
  // Each light's samples above the horizon and its unoccluded light first: the lights share
  // the point's rays by what each brings (a probe given its visibility casts none).
  thread_local std::vector<SeenLight> seen;  // reused from probe to probe: no allocation
  thread_local std::vector<double> lum;
  seen.resize(lights_.size()), lum.assign(lights_.size(), 0.0);
  double open = 0;
  for (size_t t = 0; t < lights_.size(); ++t) {
    samplesAbove(p, n, t, seen[t]);
    if (!seen[t].above.empty()) open += lum[t] = luminance(lights_[t].emission) * seen[t].F;
  }
  if (!(open > 0)) return out;
  auto stride = [&](size_t t, double total) {
    return probe.visible ? 1 : sampleStride(seen[t].above.size(), lum[t] / total, raysPerPoint_);
  };
  double shown = 0;
  for (size_t t = 0; t < lights_.size(); ++t) {
    if (seen[t].above.empty()) continue;
    const size_t s = stride(t, open);
    // Clear sight is looked for where it would save many rays: a point given its ends'
    // samples casts them where those differ (many on an edge across a whole penumbra).
    const LightPolygon& light = lights_[t];
    const size_t rays = !probe.visible       ? seen[t].above.size() / s
                        : probe.alsoVisible ? bitsDiffer(*probe.visible, *probe.alsoVisible, light.first, light.count)
                                            : 0;
    if (probe.clearSight && rays >= size_t(kClearSightRays) && clearSight_->clear(p, light.rayHull)) {
      seen[t].seeWhole();
      ++seenWhole;
    } else {
      test(probe, p, s, seen[t], raysCast);
    }
    shown += lum[t] * seenShare(p, n, t, seen[t]);
  }
  // In a shadow the light that arrives is not what the open sky would bring: a light in
  // whose penumbra the point lies is tested again for its share of what is shown.
  for (size_t t = 0; t < lights_.size() && shown > 0; ++t)
    if (seen[t].stride > 1 && seen[t].partial()) test(probe, p, stride(t, shown), seen[t], raysCast);
  for (size_t t = 0; t < lights_.size(); ++t) {
    SeenLight& light = seen[t];
    if (light.above.empty()) continue;
    setBits(light.above, light.visible, out.visible);
    const glm::dvec3 full = probe.rho * lights_[t].emission * light.F;
    out.radiosity += full * seenShare(p, n, t, light);
    out.weight[t] = float(luminance(full) / double(light.above.size()));  // the mean sample's share
  }
  return out;
}

std::vector<VertexLight> DirectLight::lightAt(const std::vector<Probe>& probes) {
  std::vector<VertexLight> out(probes.size());
  if (!enabled_) return out;
  // Rays per worker, each count on its own cache line: counted per ray, they would otherwise
  // bounce one line between the cores.
  struct alignas(64) Count {
    long rays = 0, whole = 0;
  };
  std::vector<Count> cast(static_cast<size_t>(workers_));
  StageProgress progress("direct light: points", probes.size());  // said by the caller's worker
  parallelFor(
      probes.size(), workers_,
      [&](size_t k, int worker) {
        if (worker == 0) progress.update(k);
        out[k] = compute(probes[k], cast[size_t(worker)].rays, cast[size_t(worker)].whole);
      },
      64);
  for (const Count& c : cast) rays_ += c.rays, seenWhole_ += c.whole;
  return out;
}

namespace {

/// Whether vertex v's light was skipped as black (compute: a probe of reflectance 0).
bool blackVertex(const PatchMesh& mesh, int v) {
  for (auto f : mesh.mesh.vf_range(TriMesh::VertexHandle(v))) return mesh.reflectance(f.idx()) == glm::dvec3(0.0);
  return true;
}

}  // namespace

void DirectLight::update(const PatchMesh& mesh, std::unordered_map<int, VertexLight>* known,
                         const std::unordered_map<int, std::pair<int, int>>* between) {
  if (!enabled_) return;
  const size_t from = vertices_.size(), to = mesh.mesh.n_vertices();
  if (from >= to) return;
  vertices_.resize(to);
  std::vector<char> done(to - from, 0);  // per new vertex
  auto isDone = [&](int v) { return size_t(v) < from || done[size_t(v) - from]; };
  std::vector<size_t> waiting;  // vertices between two ends, waiting for those
  std::vector<Probe> probes;
  std::vector<size_t> at;
  for (size_t k = from; k < to; ++k) {
    if (known) {
      auto it = known->find(int(k));
      if (it != known->end()) {
        vertices_[k] = std::move(it->second);
        done[k - from] = 1;
        continue;
      }
    }
    if (between && between->count(int(k))) {
      waiting.push_back(k);
      continue;
    }
    probes.push_back(vertexProbe(mesh, TriMesh::VertexHandle(int(k))));
    at.push_back(k);
  }
  // Rounds: the vertices on their own first, then those whose ends are known by then (an end
  // may itself be a vertex bisection put between two others).
  while (true) {
    if (!probes.empty()) {
      std::vector<VertexLight> found = lightAt(probes);
      for (size_t i = 0; i < at.size(); ++i) vertices_[at[i]] = std::move(found[i]), done[at[i] - from] = 1;
      probes.clear(), at.clear();
    }
    if (waiting.empty()) break;
    std::vector<size_t> still;
    for (size_t k : waiting) {
      const auto [a, b] = between->at(int(k));
      if (!isDone(a) || !isDone(b)) {
        still.push_back(k);
        continue;
      }
      Probe probe = vertexProbe(mesh, TriMesh::VertexHandle(int(k)));
      // A black end saw nothing, tested or not: what its samples say is no visibility.
      if (blackVertex(mesh, a) || blackVertex(mesh, b)) {
        probes.push_back(probe);
        at.push_back(k);
        continue;
      }
      probe.visible = &vertices_[size_t(a)].visible;
      if (vertices_[size_t(b)].visible != *probe.visible) probe.alsoVisible = &vertices_[size_t(b)].visible;
      probes.push_back(probe);
      at.push_back(k);
    }
    if (probes.empty()) {  // ends that never come (not vertices bisection made): on their own
      for (size_t k : still) probes.push_back(vertexProbe(mesh, TriMesh::VertexHandle(int(k)))), at.push_back(k);
      still.clear();
    }
    waiting = std::move(still);
  }
}

std::vector<glm::dvec3> DirectLight::radiosity() const {
  std::vector<glm::dvec3> out;
  out.reserve(vertices_.size());
  for (const auto& v : vertices_) out.push_back(v.radiosity);
  return out;
}

}  // namespace rad
