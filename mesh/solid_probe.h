#pragma once
// Internal to buildPatchMesh: whether a point lies inside a solid, by rays against the planar
// pieces. Contact lines only suggest which parts of a surface are hidden (a footprint, the
// strip of a side wall inside a partition); the rays decide, so that a face whose lit side
// looks into open air (a doorway's jamb, a window's reveal) is kept.
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/planar_pieces.h"
#include "mesh/surface_rays.h"

namespace rad::meshing {

/// Rays against a set of pieces (mesh/surface_rays.h over their polygons).
class SolidProbe {
 public:
  /// Indexes `pieces` (their points in `table`); the scene says which surfaces are two-sided.
  SolidProbe(const Scene& scene, const PointTable& table, const std::vector<Piece>& pieces);

  /// Whether the point p of a surface whose lit side faces `normal` is inside a solid: from just
  /// off the surface, most of a fixed set of rays over that hemisphere (cosine-spread) first
  /// meet the back of a one-sided surface. Rays that meet a front, a two-sided surface or
  /// nothing vote for open air.
  bool insideSolid(const glm::dvec3& p, const glm::dvec3& normal) const;

 private:
  std::vector<Polygon> polygons_;  ///< the pieces as polygons (first ring outer, others holes)
  std::vector<bool> twoSided_;
  SurfaceRays rays_;
  double offset_ = 0;  ///< how far off the surface the rays start
};

}  // namespace rad::meshing
