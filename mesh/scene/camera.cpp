#include "mesh/scene/camera.h"

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "mesh/base/error.h"

namespace rad {
namespace {

/// The shortest text of a number, as the messages show it.
std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

Camera framingCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax, const glm::dvec3& towardsEye) {
  Camera c;
  c.fovYDeg = 45;
  c.target = (boundsMin + boundsMax) * 0.5;
  double radius = glm::length(boundsMax - boundsMin) * 0.5;
  if (!(radius > 0)) radius = kPointBoxRadius;
  const double distance = radius / std::sin(glm::radians(c.fovYDeg) * 0.5);
  c.eye = c.target + glm::normalize(towardsEye) * distance;
  c.up = glm::dvec3(0, 1, 0);
  return c;
}

Camera defaultCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax) {
  return framingCamera(boundsMin, boundsMax, glm::dvec3(0, 0, -1));
}

void checkCamera(const Camera& c, const std::string& where) {
  for (double v : {c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                   c.up.z, c.fovYDeg})
    if (!std::isfinite(v)) throw inputError(where, "finite camera values", "a non-finite value");
  if (!(c.fovYDeg > 0 && c.fovYDeg < 180))
    throw inputError(where, "a vertical field of view in (0, 180) degrees", fmt(c.fovYDeg));
  const glm::dvec3 forward = c.target - c.eye;
  if (glm::length(forward) == 0) throw inputError(where, "an eye distinct from the target", "the same point");
  if (glm::length(glm::cross(forward, c.up)) <= 1e-12 * glm::length(forward) * glm::length(c.up))
    throw inputError(where, "an up vector not parallel to the view direction", "a parallel one");
}

}  // namespace rad
