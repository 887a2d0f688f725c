// Clear sight (radiosity/light/clear_sight.h): whether anything stands between a point and a light,
// against the pyramid the point's shadow rays fill.
#include <array>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "radiosity/formfactors/element_hierarchy.h"
#include "radiosity/light/clear_sight.h"

namespace rad {
namespace {

/// Single-precision rays: elements nearer than this to the pyramid count as in it.
constexpr double kMargin = 1e-7;

/// The triangles as an element hierarchy.
ElementHierarchy triangles(const std::vector<std::array<glm::dvec3, 3>>& list) {
  std::vector<glm::dvec3> positions, normals;
  std::vector<uint32_t> indices;
  for (const auto& t : list) {
    for (const glm::dvec3& p : t) indices.push_back(uint32_t(positions.size())), positions.push_back(p);
    normals.push_back(glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0])));
  }
  return ElementHierarchy(positions, indices, normals);
}

/// A 1 m square light 2 m above the point (0, 0, 0), facing down.
const std::vector<glm::dvec3> kLight = {{-0.5, 2, -0.5}, {0.5, 2, -0.5}, {0.5, 2, 0.5}, {-0.5, 2, 0.5}};
const glm::dvec3 kApex(0.0);

/// A small horizontal triangle at height y round (x, z).
std::array<glm::dvec3, 3> tile(double x, double y, double z, double size = 0.05) {
  return {glm::dvec3(x, y, z), glm::dvec3(x + size, y, z), glm::dvec3(x, y, z + size)};
}

TEST(ClearSightTest, AnythingInThePyramidBlocksIt) {
  // Halfway up, the pyramid is 0.5 m across: a tile at its middle or just inside a side
  // blocks it; one just outside a side, or far away, does not.
  EXPECT_FALSE(ClearSight(triangles({tile(0, 1, 0)}), kMargin).clear(kApex, kLight));
  EXPECT_FALSE(ClearSight(triangles({tile(0.24, 1, 0)}), kMargin).clear(kApex, kLight));
  EXPECT_TRUE(ClearSight(triangles({tile(0.26, 1, 0)}), kMargin).clear(kApex, kLight));
  EXPECT_TRUE(ClearSight(triangles({tile(3, 1, 3), tile(-2, 0.5, 0), tile(0, 3, 0)}), kMargin).clear(kApex, kLight));
  // A long sliver crossing the pyramid with every corner outside it blocks it too.
  EXPECT_FALSE(ClearSight(triangles({{glm::dvec3(-2, 1, 0), glm::dvec3(2, 1, 0), glm::dvec3(2, 1, 0.01)}}), kMargin)
                   .clear(kApex, kLight));
}

TEST(ClearSightTest, TheSurfacesAtEitherEndDoNotBlockIt) {
  // The floor the point stands on (just below it) and the light's own plane (just beyond
  // the base) are apart from the pyramid; a wall reaching into it is not.
  const std::array<glm::dvec3, 3> floor = {glm::dvec3(-5, -1e-5, 5), glm::dvec3(5, -1e-5, 5),
                                           glm::dvec3(0, -1e-5, -5)};
  const std::array<glm::dvec3, 3> ceiling = {glm::dvec3(-5, 2 + 1e-5, -5), glm::dvec3(5, 2 + 1e-5, -5),
                                             glm::dvec3(0, 2 + 1e-5, 5)};
  EXPECT_TRUE(ClearSight(triangles({floor, ceiling}), kMargin).clear(kApex, kLight));
  const std::array<glm::dvec3, 3> wall = {glm::dvec3(0.4, 0, -5), glm::dvec3(0.4, 0, 5), glm::dvec3(0.4, 5, 0)};
  EXPECT_FALSE(ClearSight(triangles({floor, ceiling, wall}), kMargin).clear(kApex, kLight));
}

TEST(ClearSightTest, ALightSeenEdgeOnIsNeverClear) {
  EXPECT_FALSE(ClearSight(triangles({tile(5, 5, 5)}), kMargin).clear(glm::dvec3(3, 2, 0), kLight));
}

}  // namespace
}  // namespace rad
