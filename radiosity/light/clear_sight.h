#pragma once
// Whether a point sees the whole of a light: no occluder meets the space between them.
//
// A shadow ray runs from the point to a sample on the light, so every ray of the point lies in
// the convex hull of the point and the light's outline (a pyramid with the point as apex).
// When no element of the scene comes within a margin of that pyramid, every ray would come
// back unblocked, and none need be cast: in an open room most points see every light whole,
// and only those near a shadow pay for their rays. The test is conservative: an element it
// cannot separate from the pyramid (by the pyramid's own planes or the element's plane) makes
// it answer "not clear", and the rays are cast as before.
#include <vector>

#include <glm/vec3.hpp>

#include "radiosity/formfactors/element_hierarchy.h"

namespace rad {

class ClearSight {
 public:
  /// `occluders`: every element a ray can hit. `margin`: how far (scene units) an element
  /// must stay off the pyramid to count as apart (rays are single precision).
  ClearSight(const ElementHierarchy& occluders, double margin) : occluders_(occluders), margin_(margin) {}

  /// Whether no occluder meets the hull of `apex` and the convex polygon `base` (its corners
  /// in order, either way round). A base seen edge-on (apex in its plane) is never clear.
  bool clear(const glm::dvec3& apex, const std::vector<glm::dvec3>& base) const;

 private:
  struct Plane {
    glm::dvec3 normal;  ///< outwards
    double offset;      ///< a point x is outside when dot(normal, x) > offset
  };
  /// The pyramid's bounding planes, or false when it is degenerate.
  bool pyramid(const glm::dvec3& apex, const std::vector<glm::dvec3>& base, std::vector<Plane>& planes) const;
  /// Whether the triangle abc is apart from the pyramid: outside one of its planes, or the
  /// pyramid's corners all on one side of the triangle's plane.
  bool apart(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& normal,
             const glm::dvec3& apex, const std::vector<glm::dvec3>& base, const std::vector<Plane>& planes) const;

  const ElementHierarchy& occluders_;
  double margin_;
};

}  // namespace rad
