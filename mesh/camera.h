#pragma once
// The camera rules shared by the solver (the result file's camera) and the viewer: the default
// view of a scene or mesh without a camera, and the check that a camera can be used.
#include <string>

#include <glm/vec3.hpp>

#include "mesh/scene.h"

namespace rad {

/// Radius (scene units) taken for a bounding box that is a single point, so that the eye stays
/// away from the target.
constexpr double kPointBoxRadius = 1e-9;

/// A camera for a box [boundsMin, boundsMax] seen without one: looking along +z at the box's
/// centre, up +y, a 45° vertical field of view, from far enough that the box's bounding sphere
/// fills the view's height.
Camera defaultCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax);

/// defaultCamera of the bounding box of the scene's polygons (their outer rings).
Camera defaultCamera(const Scene& scene);

/// Checks a camera for finite values, a vertical field of view in (0, 180) degrees, an eye away
/// from the target and an up vector not parallel to the view; `where` names the source. Throws
/// InputError.
void checkCamera(const Camera& camera, const std::string& where);

}  // namespace rad
