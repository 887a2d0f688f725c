#pragma once
// Internal to buildPatchMesh: whether a point lies inside a solid, by rays against the planar
// pieces. Contact lines only suggest which parts of a surface are hidden (a footprint, the
// strip of a side wall inside a partition); the rays decide, so that a face whose lit side
// looks into open air (a doorway's jamb, a window's reveal) is kept.
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/planar_pieces.h"

namespace rad::meshing {

/// Rays against a set of pieces, through a bounding-volume hierarchy over their boxes.
class SolidProbe {
 public:
  /// Indexes `pieces` (their points in `table`); the scene says which surfaces are two-sided.
  SolidProbe(const Scene& scene, const PointTable& table, const std::vector<Piece>& pieces);

  /// Whether the point p of a surface whose lit side faces `normal` is inside a solid: from just
  /// off the surface, most of a fixed set of rays over that hemisphere (cosine-spread) first
  /// meet the back of a one-sided surface. Rays that meet a front, a two-sided surface or
  /// nothing vote for open air.
  bool insideSolid(const glm::dvec3& p, const glm::dvec3& normal) const;

 private:
  struct Node {
    glm::dvec3 lo, hi;
    int first = 0, count = 0;  ///< a leaf's pieces in order_; count 0: an inner node
    int right = 0;             ///< an inner node's second child (its first follows it)
  };
  struct Hit {
    int piece = -1;
    double t = 0;
  };

  int build(int first, int count);
  Hit firstHit(const glm::dvec3& origin, const glm::dvec3& dir) const;
  void hitLeaf(const Node& node, const glm::dvec3& origin, const glm::dvec3& dir, Hit& best) const;
  bool hitsPiece(int piece, const glm::dvec3& origin, const glm::dvec3& dir, double& t) const;

  std::vector<PlaneFrame> frames_;
  std::vector<Polygon2> rings_;     ///< each piece's rings in its frame
  std::vector<bool> twoSided_;
  std::vector<glm::dvec3> lo_, hi_;  ///< each piece's box
  std::vector<int> order_;
  std::vector<Node> nodes_;
  double offset_ = 0;  ///< how far off the surface the rays start
};

}  // namespace rad::meshing
