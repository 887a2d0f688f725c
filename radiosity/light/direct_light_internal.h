#pragma once
// Internal to direct light (radiosity/light/: direct_light, light_rays, vertex_probes,
// sample_visibility, light_at_point): the ray offset, runs of samples, and Embree's scene of the
// elements the rays are cast against. Not a public header.
#include <cstddef>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "radiosity/light/direct_light.h"

namespace rad {
namespace direct_light {

/// Ray ends are moved this far (relative to the scene size) off their surfaces: off the
/// receiver along its normal and towards its own elements (a vertex at the foot of a wall
/// must not start its rays inside the wall's plane), and off the emitter along its normal.
constexpr double kRayOffset = 1e-5;

/// Whether the (ascending) sample indices are consecutive: a light's run of samples, wholly
/// above a point's horizon, which its bit words and axis arrays hold in order.
inline bool isRun(const std::vector<int>& samples) {
  return !samples.empty() && size_t(samples.back() - samples.front()) + 1 == samples.size();
}

}  // namespace direct_light

/// Embree's device and scene: every element, in coordinates (p − centre)/size so that single
/// precision holds at any scene scale.
struct DirectLight::Rays {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  glm::dvec3 centre{0.0};
  double scale = 1;

  ~Rays();

  /// centre and scale: the mesh's bounding box.
  void frame(const PatchMesh& mesh);
  /// Embree's scene of every element of the mesh, normalised to its bounding box.
  void build(const PatchMesh& mesh);

  /// The segment from a to b (scene coordinates) as Embree's ray, normalised.
  RTCRay segment(const glm::dvec3& a, const glm::dvec3& b) const;

  /// Rays per packet: the widest Embree traverses natively on this processor (8 with AVX2,
  /// where 16 are taken as two 8s and cost a sixth more in all).
  int packet = 4;

  /// Whether each segment from a to a point of `to` is blocked, in packets of rays from one
  /// origin (coherent: Embree traverses each packet together).
  void blocked(const glm::dvec3& a, const std::vector<glm::dvec3>& to, std::vector<char>& out) const;

  /// blocked() in packets of N rays, `occluded` Embree's test for that width.
  template <class Packet, size_t N, class Occluded>
  void blockedIn(const glm::dvec3& a, const std::vector<glm::dvec3>& to, std::vector<char>& out,
                 Occluded occluded) const;
};

}  // namespace rad
