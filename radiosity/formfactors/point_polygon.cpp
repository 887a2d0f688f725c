#include "radiosity/formfactors/point_polygon.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace rad {
namespace {

/// Sutherland–Hodgman against the plane n·(p − x) ≥ 0: the part of the polygon above the
/// point's tangent plane (the rest is below the horizon).
std::vector<glm::dvec3> clipToHemisphere(const glm::dvec3& x, const glm::dvec3& n,
                                         const std::vector<glm::dvec3>& polygon) {
  std::vector<glm::dvec3> out;
  size_t m = polygon.size();
  for (size_t i = 0; i < m; ++i) {
    const glm::dvec3& a = polygon[i];
    const glm::dvec3& b = polygon[(i + 1) % m];
    double da = glm::dot(n, a - x), db = glm::dot(n, b - x);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

}  // namespace

namespace {

/// Lambert's contour sum Σᵢ γᵢ n·(Rᵢ×Rᵢ₊₁)/|Rᵢ×Rᵢ₊₁| over a polygon wholly above x's tangent
/// plane, signed by the polygon's winding.
double contourSum(const glm::dvec3& x, const glm::dvec3& n, const std::vector<glm::dvec3>& p) {
  double sum = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    glm::dvec3 r0 = p[i] - x, r1 = p[(i + 1) % p.size()] - x;
    glm::dvec3 c = glm::cross(r0, r1);
    double len = glm::length(c);
    if (len == 0) continue;  // an edge through x, or of zero length: contributes nothing
    double gamma = std::atan2(len, glm::dot(r0, r1));
    sum += gamma * glm::dot(n, c) / len;
  }
  return sum;
}

/// The contour sum of the part of the polygon above x's tangent plane.
double clippedContourSum(const glm::dvec3& x, const glm::dvec3& n, const std::vector<glm::dvec3>& polygon) {
  // Wholly above the horizon or wholly below it, as most lights are from most points, the
  // polygon needs no clipping (the clipped copy would be the same corners in the same order).
  size_t above = 0;
  for (const glm::dvec3& a : polygon) above += glm::dot(n, a - x) >= 0;
  if (above == 0 || polygon.size() < 3) return 0.0;
  if (above == polygon.size()) return contourSum(x, n, polygon);
  const std::vector<glm::dvec3> p = clipToHemisphere(x, n, polygon);
  return p.size() < 3 ? 0.0 : contourSum(x, n, p);
}

}  // namespace

double pointPolygonFormFactor(const glm::dvec3& x, const glm::dvec3& n,
                              const std::vector<glm::dvec3>& polygon) {
  return std::abs(clippedContourSum(x, n, polygon)) / (2 * M_PI);
}

double pointRegionFormFactor(const glm::dvec3& x, const glm::dvec3& n,
                             const std::vector<std::vector<glm::dvec3>>& loops) {
  double sum = 0;
  for (const auto& loop : loops) sum += clippedContourSum(x, n, loop);
  return std::abs(sum) / (2 * M_PI);
}

}  // namespace rad
