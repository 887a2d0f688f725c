// Planar pieces ▸ pieces in one plane: what covers what, and which edges are a surface's own.
#include "mesh/coplanar_pieces.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "mesh/scene/geometry.h"

namespace rad::meshing {
namespace {

/// Normals this close (their dot product) are one direction.
constexpr double kSameDirection = 1 - 1e-9;

/// Whether the edge from a to b crosses the ray from x along +u (even-odd rule).
bool crossesRay(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& x) {
  const glm::dvec2 d = b - a;
  return (a.y > x.y) != (b.y > x.y) && x.x < a.x + (x.y - a.y) * d.x / d.y;
}

/// The area of one ring of a piece.
double ringArea(const PointTable& table, const Piece& piece, const std::vector<int>& ring) {
  double twice = 0;
  for (size_t k = 0; k < ring.size(); ++k) {
    const auto [a, b] = projectedEdge(table, piece, ring, k);
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * std::abs(twice);
}

/// Each surface's area: its pieces' outlines less their holes, however they wind.
std::vector<double> surfaceAreas(const Scene& scene, const PointTable& table, const std::vector<Piece>& pieces) {
  std::vector<double> area(scene.surfaces.size(), 0.0);
  for (const Piece& piece : pieces)
    for (size_t r = 0; r < piece.rings.size(); ++r)
      area[size_t(piece.surface)] += (r == 0 ? 1 : -1) * ringArea(table, piece, piece.rings[r]);
  return area;
}

/// The pieces whose rings have each edge (point ids, lower first).
std::map<std::pair<int, int>, std::vector<int>> ringEdgeUsers(const std::vector<Piece>& pieces) {
  std::map<std::pair<int, int>, std::vector<int>> users;
  for (size_t p = 0; p < pieces.size(); ++p)
    for (const auto& ring : pieces[p].rings)
      for (size_t k = 0; k < ring.size(); ++k) users[std::minmax(ring[k], ring[(k + 1) % ring.size()])].push_back(int(p));
  return users;
}

}  // namespace

std::pair<glm::dvec2, glm::dvec2> projectedEdge(const PointTable& table, const Piece& piece,
                                                const std::vector<int>& ring, size_t k) {
  return {piece.frame.project(table[ring[k]]), piece.frame.project(table[ring[(k + 1) % ring.size()]])};
}

Place placeIn(const PointTable& table, const Piece& piece, const glm::dvec3& q, double tolerance) {
  const glm::dvec2 x = piece.frame.project(q);
  bool inside = false;
  for (const auto& ring : piece.rings)
    for (size_t k = 0; k < ring.size(); ++k) {
      const auto [a, b] = projectedEdge(table, piece, ring, k);
      if (segmentDistance(x, a, b) <= tolerance) return Place::Border;
      if (crossesRay(a, b, x)) inside = !inside;
    }
  return inside ? Place::Inside : Place::Outside;
}

CoplanarPieces::CoplanarPieces(const Scene& scene, const PointTable& table, const std::vector<Piece>& pieces,
                               double tolerance)
    : scene_(scene), table_(table), pieces_(pieces), tolerance_(tolerance),
      surfaceArea_(surfaceAreas(scene, table, pieces)), edgeUsers_(ringEdgeUsers(pieces)) {}

bool CoplanarPieces::overlap(size_t r, size_t s) const {
  const Piece &pr = pieces_[r], &ps = pieces_[s];
  auto inside = [&](const Piece& piece, const glm::dvec3& q) { return placeIn(table_, piece, q, tolerance_) == Place::Inside; };
  glm::dvec3 centroid(0.0);
  for (int id : ps.rings[0]) centroid += table_[id] / double(ps.rings[0].size());
  if (inside(pr, centroid)) return true;
  for (const auto& ring : ps.rings)
    for (int id : ring)
      if (inside(pr, table_[id])) return true;
  for (const auto& ring : pr.rings)
    for (int id : ring)
      if (inside(ps, table_[id])) return true;
  return false;
}

bool CoplanarPieces::covers(size_t s, size_t r) const {
  const Piece &pr = pieces_[r], &ps = pieces_[s];
  if (!(glm::dot(pr.frame.normal, ps.frame.normal) >= kSameDirection)) return false;  // NaN: not coplanar
  const auto& surfaces = scene_.surfaces;
  if (surfaces[size_t(pr.surface)].twoSided && !surfaces[size_t(ps.surface)].twoSided) return false;  // r's back shows
  for (const auto& ring : ps.rings)
    for (int id : ring)
      if (std::abs(glm::dot(pr.frame.normal, table_[id] - pr.frame.origin)) > tolerance_) return false;
  if (!overlap(r, s)) return false;  // a lamp filling the ceiling's hole covers nothing
  const double ar = surfaceArea_[size_t(pr.surface)], as = surfaceArea_[size_t(ps.surface)];
  if (as != ar) return as < ar;
  return ps.surface != pr.surface ? ps.surface > pr.surface : s > r;
}

std::set<std::pair<int, int>> CoplanarPieces::innerEdges(size_t r) const {
  std::set<std::pair<int, int>> inner;
  const Piece& pr = pieces_[r];
  for (const auto& ring : pr.rings)
    for (size_t k = 0; k < ring.size(); ++k) {
      const auto edge = std::minmax(ring[k], ring[(k + 1) % ring.size()]);
      for (int s : edgeUsers_.at(edge)) {
        const Piece& ps = pieces_[size_t(s)];
        if (size_t(s) != r && ps.surface == pr.surface && glm::dot(ps.frame.normal, pr.frame.normal) >= kSameDirection)
          inner.insert(edge);
      }
    }
  return inner;
}

}  // namespace rad::meshing
