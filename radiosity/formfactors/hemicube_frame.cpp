#include "radiosity/formfactors/hemicube_frame.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace rad {

HemicubeFrame HemicubeFrame::make(const glm::dvec3& x, const glm::dvec3& n, double rotation,
                                  double eyeOffset) {
  // A tangent least aligned with n, turned about n by 2π·rotation.
  const glm::dvec3 t = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u0 = glm::normalize(glm::cross(n, t)), v0 = glm::cross(n, u0);
  const double angle = 2 * M_PI * rotation;
  const glm::dvec3 u = std::cos(angle) * u0 + std::sin(angle) * v0;
  return {x + eyeOffset * n, u, glm::cross(n, u), n};
}

}  // namespace rad
