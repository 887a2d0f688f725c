#pragma once
// The camera rules shared by the solver (the result file's camera) and the viewer: the view of a
// bare bounding box, and the check that a camera can be used. The default camera of a scene or a
// result, which looks at what it is, is mesh/results/default_camera.h.
#include <string>

#include <glm/vec3.hpp>

#include "mesh/scene/scene.h"

namespace rad {

/// Radius (scene units) taken for a bounding box that is a single point, so that the eye stays
/// away from the target.
constexpr double kPointBoxRadius = 1e-9;

/// A camera looking at the centre of the box [boundsMin, boundsMax] from the side `towardsEye`
/// points to (any length but zero, not along +y), up +y, with a 45° vertical field of view, from
/// far enough that the box's bounding sphere fills the view's height.
Camera framingCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax, const glm::dvec3& towardsEye);

/// A camera for a box seen without one: framingCamera looking along +z.
Camera defaultCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax);

/// Checks a camera for finite values, a vertical field of view in (0, 180) degrees, an eye away
/// from the target and an up vector not parallel to the view; `where` names the source. Throws
/// InputError.
void checkCamera(const Camera& camera, const std::string& where);

}  // namespace rad
