#pragma once
// Internal to buildPatchMesh: planar pieces in one plane. Where a point lies in a piece; which
// pieces lie on others and cover them (a rug on a floor, a face the file has twice); which of a
// piece's edges it shares with another face of its surface in its plane (a floor's diagonal).
#include <map>
#include <set>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mesh/planar_pieces.h"

namespace rad::meshing {

/// Edge k of one of the piece's rings, in the piece's frame.
std::pair<glm::dvec2, glm::dvec2> projectedEdge(const PointTable& table, const Piece& piece,
                                                const std::vector<int>& ring, size_t k);

/// Where a point of a piece's plane lies: inside it, outside, or within a tolerance of its border.
enum class Place { Inside, Outside, Border };
Place placeIn(const PointTable& table, const Piece& piece, const glm::dvec3& q, double tolerance);

/// True when q, a point of s's plane, lies inside piece s or within `tolerance` of its border.
inline bool insideOrOn(const PointTable& table, const Piece& s, const glm::dvec3& q, double tolerance) {
  return placeIn(table, s, q, tolerance) != Place::Outside;
}

class CoplanarPieces {
 public:
  /// Pieces in one plane are those within `tolerance` of it (the contact tolerance).
  CoplanarPieces(const Scene& scene, const PointTable& table, const std::vector<Piece>& pieces,
                 double tolerance);

  /// Whether piece s lies on piece r, in its plane and facing its way, and covers it where they
  /// overlap: the one in front wins, and between two in one plane, what lies on a surface is
  /// the smaller (a rug on a floor, a painting on a wall; a floor of many tiles is one
  /// surface, so it is the rug that wins); of two alike (a duplicated face), the later in the
  /// file. Never a one-sided piece over a two-sided one (whose back shows).
  bool covers(size_t s, size_t r) const;

  /// The edges (point ids, lower first) of piece r's rings that it shares with another piece of
  /// its surface in its plane, facing its way.
  std::set<std::pair<int, int>> innerEdges(size_t r) const;

 private:
  /// Whether coplanar pieces r and s overlap: a corner of either, or the centroid of s's
  /// outline, lies inside the other beyond the tolerance (two equal faces share only their
  /// centroid; a lamp filling a ceiling's hole has its corners on the hole's border and its
  /// centroid in the hole). Edges that cross with no corner inside (a cross of two strips) go
  /// unseen.
  bool overlap(size_t r, size_t s) const;

  const Scene& scene_;
  const PointTable& table_;
  const std::vector<Piece>& pieces_;
  const double tolerance_;
  std::vector<double> surfaceArea_;  ///< per surface: its pieces' outlines less their holes
  std::map<std::pair<int, int>, std::vector<int>> edgeUsers_;  ///< pieces whose rings have each edge
};

}  // namespace rad::meshing
