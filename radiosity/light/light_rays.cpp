// Direct light ▸ rays: Embree's scene of the mesh's elements, normalised to its bounding box,
// and the shadow rays cast against it in packets from one origin.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "radiosity/light/direct_light_internal.h"

namespace rad {

DirectLight::Rays::~Rays() {
  if (scene) rtcReleaseScene(scene);
  if (device) rtcReleaseDevice(device);
}

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

RTCRay DirectLight::Rays::segment(const glm::dvec3& a, const glm::dvec3& b) const {
  const glm::dvec3 o = (a - centre) / scale, d = (b - a) / scale;
  RTCRay ray{};
  ray.org_x = float(o.x), ray.org_y = float(o.y), ray.org_z = float(o.z);
  ray.dir_x = float(d.x), ray.dir_y = float(d.y), ray.dir_z = float(d.z);
  ray.tnear = 0.0f;
  ray.tfar = 1.0f;
  ray.mask = 0xFFFFFFFFu;
  return ray;
}

template <class Packet, size_t N, class Occluded>
void DirectLight::Rays::blockedIn(const glm::dvec3& a, const std::vector<glm::dvec3>& to, std::vector<char>& out,
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

void DirectLight::Rays::blocked(const glm::dvec3& a, const std::vector<glm::dvec3>& to,
                                std::vector<char>& out) const {
  out.assign(to.size(), 0);
  if (packet == 16)
    blockedIn<RTCRay16, 16>(a, to, out, rtcOccluded16);
  else if (packet == 8)
    blockedIn<RTCRay8, 8>(a, to, out, rtcOccluded8);
  else
    blockedIn<RTCRay4, 4>(a, to, out, rtcOccluded4);
}

}  // namespace rad
