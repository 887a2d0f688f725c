#pragma once
// The exact unoccluded form factor from a point to a planar polygon.
#include <vector>

#include <glm/vec3.hpp>

namespace rad {

/// Form factor from a differential area at x with unit normal n to the planar polygon, by
/// Lambert's contour formula (oracles.md §1): the polygon is first clipped to the half-space
/// n·(p − x) ≥ 0, then F = (1/2π)|Σᵢ γᵢ n·(Rᵢ×Rᵢ₊₁)/|Rᵢ×Rᵢ₊₁||, Rᵢ = Pᵢ − x,
/// γᵢ = atan2(|Rᵢ×Rᵢ₊₁|, Rᵢ·Rᵢ₊₁). Occlusion is ignored. Dimensionless, in [0, 1].
double pointPolygonFormFactor(const glm::dvec3& x, const glm::dvec3& n,
                              const std::vector<glm::dvec3>& polygon);

/// The same for a planar region bounded by several loops (an outline and its holes, the holes
/// wound the other way): the contour integral is a sum over the loops, each clipped alone.
double pointRegionFormFactor(const glm::dvec3& x, const glm::dvec3& n,
                             const std::vector<std::vector<glm::dvec3>>& loops);

}  // namespace rad
