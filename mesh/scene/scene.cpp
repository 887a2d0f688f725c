// The scene's own questions: does anything glow, and how big is it.
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/scene/scene.h"

namespace rad {

bool Scene::hasEmitter() const {
  for (const auto& s : surfaces)
    if (materials[s.material].emits()) return true;
  return false;
}

double Scene::diagonal() const {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const auto& s : surfaces)
    for (const auto& p : s.polygons)
      for (const auto& q : p.outer) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
      }
  return lo.x <= hi.x ? glm::length(hi - lo) : 0.0;
}

}  // namespace rad
