#pragma once
// Cutting a planar polygon along the lines where other surfaces touch or pierce it, and
// leaving out what those surfaces enclose. The CGAL implementation (2D arrangements, exact
// constructions) stays behind this header.
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "mesh/polygon_mesher.h"

namespace rad {

/// Where another surface meets the polygon, in the polygon's 2D frame.
struct ContactLine2 {
  glm::dvec2 a{0.0}, b{0.0};
  int aId = -1, bId = -1;  ///< the caller's ids of the ends, or -1
  /// Which side of a→b the touching surface's back (its solid side) faces: +1 left, -1
  /// right, 0 neither (a two-sided surface).
  int solid = 0;
  /// An edge of a surface lying on this one, in its plane and facing its way (a rug on a
  /// floor): what it covers is left out (coveredBy decides), and it closes nothing.
  bool cover = false;
};

/// The polygon cut along the contact lines.
struct ContactCut {
  /// What is kept: rings (outer boundaries and holes, any nesting) and, as lines, the contact
  /// lines that run inside it. Ids: the polygon's and the contacts' ids where a point is one
  /// of theirs, -1 for points the cut made (crossings).
  Polygon2 kept;
  /// For each edge of kept.rings (edge k runs from point k to k + 1): whether it is a contact
  /// line inside the original polygon (not along its boundary). Lines always are.
  std::vector<std::vector<bool>> contactEdge;
  /// The parts left out: area, and the contacts (indices) whose solid side enclosed each.
  struct Removed {
    double area = 0;
    std::vector<int> by;
  };
  std::vector<Removed> removed;
};

/// Whether a point of the polygon's plane (in its 2D frame) lies inside a solid; or, as
/// `covered`, under a surface lying on the polygon.
using InsideSolid = std::function<bool(const glm::dvec2&)>;

/// Cuts `polygon` along `contacts` and leaves out every part of it that the contacts enclose
/// and that lies inside a solid. Enclosed: all of the part's edges are contact lines with their
/// solid side towards it, or edges of the polygon on which another surface stands, and at
/// least one is such a solid side (a block standing on a floor, also when pushed into a wall or
/// a corner; but also a doorway's jamb between the wall's two faces). Inside a solid:
/// `insideSolid` says so at a point inside the part (the footprint, not the jamb). Contact lines with
/// kept parts on both sides stay in the kept polygon as lines (a board resting on a wall).
/// An edge the polygon shares with another face of its surface in its plane (`innerEdges`, the
/// polygon's ids, lower first: a floor's diagonal) closes a part too, so that a footprint over
/// several coplanar pieces is enclosed in each. Known limit of this rule: a footprint split by
/// another contact line (overlapping blocks, a panel through it) keeps the parts not enclosed
/// on every side.
/// With cover lines among the contacts, every part that `covered` says lies under a surface
/// lying on the polygon is left out too.
ContactCut cutAlongContacts(const Polygon2& polygon, const std::vector<ContactLine2>& contacts,
                            const InsideSolid& insideSolid, const InsideSolid& covered = {},
                            const std::set<std::pair<int, int>>& innerEdges = {});

}  // namespace rad
