#pragma once
// Rays against a list of polygons, for choices made once per scene (facing, solids, the default
// camera): the nearest polygon a ray meets and which side of it. Embree finds the polygons
// whose boxes the ray crosses; each is met or missed in double precision.
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/scene/scene.h"

namespace rad {

/// What a ray met.
struct RayHit {
  double t = 0;        ///< distance along the ray (scene units for a unit direction)
  int polygon = -1;    ///< index into the polygons given
  bool front = false;  ///< met from its lit side, or a two-sided polygon
};

/// The first polygon along a ray, among polygons kept by reference (they must outlive it).
/// Rays may be cast from several threads at once.
class SurfaceRays {
 public:
  /// Indexes `polygons` (a non-planar one as its best-fit plane); twoSided[i] says whether
  /// polygon i is lit on both sides. Zero-area polygons are never met.
  SurfaceRays(const std::vector<Polygon>& polygons, const std::vector<bool>& twoSided);
  ~SurfaceRays();
  SurfaceRays(const SurfaceRays&) = delete;
  SurfaceRays& operator=(const SurfaceRays&) = delete;

  /// The nearest polygon the ray from `origin` along `dir` meets at t > after (>= 0); with
  /// `throughBacks` the backs of one-sided polygons are passed, as a renderer culling back faces
  /// would. Of polygons met at the same t, the one given first.
  std::optional<RayHit> firstHit(const glm::dvec3& origin, const glm::dvec3& dir, bool throughBacks,
                                 double after = 0) const;

 private:
  /// The polygons as the rays test them, and their Embree scene (Embree stays in the .cpp).
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

}  // namespace rad
