#pragma once
// Whole boxes of elements against a hemicube: below its base plane (nothing of them shows),
// or hidden on every face they reach behind what the faces already hold. Both answers are
// conservative: a box said culled holds no triangle that could win a pixel centre.
#include <array>

#include <glm/vec3.hpp>

#include "radiosity/formfactors/hemicube_depth_pyramid.h"
#include "radiosity/formfactors/hemicube_frame.h"

namespace rad {

/// What a hemicube's faces hold so far: each face's depth pyramid, the top face's resolution
/// R (sides R × R/2) and the near plane.
struct HemicubeDepths {
  const std::array<DepthPyramid, 5>& pyramids;
  int resolution;
  double near;
};

/// Relative room between a box's nearest possible depth and the depths that hide it: covers
/// the raster's float depths (interpolated, stepped along rows) with a wide margin.
constexpr double kHiddenDepthMargin = 1e-3;

/// Whether no point of box [lo, hi] lies above the cube's base plane, with room for the
/// round-off of the per-vertex test (which keeps a triangle with a corner at c > 0).
bool boxBelowBase(const HemicubeFrame& frame, const glm::dvec3& lo, const glm::dvec3& hi);

/// Whether box [lo, hi] is hidden: on every face that may show part of it, each pixel its
/// projection may cover (one pixel of margin) already holds a depth greater than the box's
/// nearest point on that face could give. A box reaching the near plane of a face it shows
/// on is never hidden.
bool boxHidden(const HemicubeFrame& frame, const glm::dvec3& lo, const glm::dvec3& hi,
               const HemicubeDepths& depths);

}  // namespace rad
