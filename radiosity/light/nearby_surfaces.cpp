// Direct light ▸ nearby surfaces: how much of a vertex's hemisphere another surface fills within
// a given reach, by short rays cast against the elements the direct light's rays are.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "mesh/base/parallel.h"
#include "mesh/base/random.h"
#include "mesh/scene/geometry.h"
#include "radiosity/light/direct_light.h"
#include "radiosity/light/direct_light_internal.h"

namespace rad {
namespace {

/// The seed of the short rays' jitter: each vertex draws its own stream of it (the same on any
/// machine and any number of threads).
constexpr uint64_t kJitterSeed = 1;

/// The ends of vertex v's short rays from `origin`: kNearbyRaysPerSide² cosine-weighted
/// directions within `sin2` (the squared sine of the cone's half-angle) of `normal`,
/// stratified and jittered, each `reach` long.
std::vector<glm::dvec3> rayEnds(uint64_t v, const glm::dvec3& origin, const glm::dvec3& normal, double reach,
                                double sin2) {
  const PlaneFrame frame = planeFrame(origin, normal);
  constexpr int n = kNearbyRaysPerSide;
  Random jitter = Random::stream(kJitterSeed, v);
  std::vector<glm::dvec3> out;
  out.reserve(size_t(n * n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double s = sin2 * (i + jitter.next()) / n;
      const double phi = 2 * M_PI * (j + jitter.next()) / n;
      const double r = std::sqrt(s);
      const glm::dvec3 d = r * std::cos(phi) * frame.u + r * std::sin(phi) * frame.v + std::sqrt(1 - s) * normal;
      out.push_back(origin + reach * d);
    }
  return out;
}

}  // namespace

std::vector<int> DirectLight::surfacesWithin(const PatchMesh& mesh, const std::vector<double>& reach,
                                             double coneDeg) const {
  std::vector<int> out(reach.size(), 0);
  if (!enabled_) return out;
  const double sin2 = std::pow(std::sin(glm::radians(std::clamp(coneDeg, 0.0, 90.0))), 2);
  parallelFor(reach.size(), workers_, [&](size_t v, int) {
    if (!(reach[v] > 0)) return;
    const TriMesh::VertexHandle handle{int(v)};
    if (mesh.mesh.is_isolated(handle)) return;  // no face: no normal, no side to look from
    const Probe probe = vertexProbe(mesh, handle);
    const glm::dvec3 origin = offSurface(probe, sceneSize_);
    const double normal = glm::length(probe.normal);
    if (!(std::abs(normal - 1) < 1e-3) || !std::isfinite(glm::length(origin))) return;
    std::vector<char> blocked;
    rays_impl_->blocked(origin, rayEnds(v, origin, probe.normal, reach[v], sin2), blocked);
    for (char b : blocked) out[v] += b ? 1 : 0;
  }, 64);
  return out;
}

}  // namespace rad
