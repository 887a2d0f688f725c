// Planar pieces ▸ rays: the vote of a hemisphere of rays on whether a point is inside a solid.
#include "mesh/solid_probe.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace rad::meshing {
namespace {

/// Rays start this far off the surface, times the scene diagonal (ten times the contact
/// tolerance: clear of round-off, well inside any wall a building has).
constexpr double kRayOffset = 1e-4;
/// The hemisphere's rays: kRaySide × kRaySide strata of a cosine-spread hemisphere, one ray
/// at the middle of each (fixed, so the answer does not depend on a seed).
constexpr int kRaySide = 8;

/// Two unit vectors that make a right-handed frame with n.
std::pair<glm::dvec3, glm::dvec3> tangents(const glm::dvec3& n) {
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(helper, n));
  return {t, glm::cross(n, t)};
}

/// The piece as a polygon: its first ring the outline, the others holes.
Polygon asPolygon(const PointTable& table, const Piece& piece) {
  Polygon polygon;
  for (size_t r = 0; r < piece.rings.size(); ++r) {
    Ring ring;
    for (int id : piece.rings[r]) ring.push_back(table[id]);
    (r == 0 ? polygon.outer : polygon.holes.emplace_back()) = std::move(ring);
  }
  return polygon;
}

/// The pieces as polygons.
std::vector<Polygon> asPolygons(const PointTable& table, const std::vector<Piece>& pieces) {
  std::vector<Polygon> out;
  for (const Piece& piece : pieces) out.push_back(asPolygon(table, piece));
  return out;
}

/// Whether each piece's surface is two-sided.
std::vector<bool> twoSidedPieces(const Scene& scene, const std::vector<Piece>& pieces) {
  std::vector<bool> out;
  for (const Piece& piece : pieces) out.push_back(scene.surfaces[size_t(piece.surface)].twoSided);
  return out;
}

}  // namespace

SolidProbe::SolidProbe(const Scene& scene, const PointTable& table, const std::vector<Piece>& pieces)
    : polygons_(asPolygons(table, pieces)), twoSided_(twoSidedPieces(scene, pieces)),
      rays_(polygons_, twoSided_), offset_(kRayOffset * scene.diagonal()) {}

bool SolidProbe::insideSolid(const glm::dvec3& p, const glm::dvec3& normal) const {
  const auto [t, b] = tangents(normal);
  const glm::dvec3 origin = p + offset_ * normal;
  int backs = 0;
  for (int i = 0; i < kRaySide; ++i)
    for (int j = 0; j < kRaySide; ++j) {
      const double u = (i + 0.5) / kRaySide, phi = 2 * M_PI * (j + 0.5) / kRaySide;
      const double r = std::sqrt(u);
      const glm::dvec3 dir = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(1 - u) * normal;
      const auto hit = rays_.firstHit(origin, dir, false);
      backs += hit && !hit->front;
    }
  return 2 * backs > kRaySide * kRaySide;
}

}  // namespace rad::meshing
