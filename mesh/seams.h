#pragma once
// Internal to buildPatchMesh: the seams of a piece, the element edges along the contact lines
// that run across it (a wall passing through a tread, a shelf's edge along a wall). Light is
// discontinuous there: the two sides see different halves of the world, and where the line
// is a wall's, one side may be outside the room. So elements do not share a vertex across a
// seam, and patches do not grow across one.
#include <array>
#include <set>
#include <utility>
#include <vector>

#include "mesh/planar_pieces.h"

namespace rad::meshing {

/// Element edges as point id pairs, lower first.
using EdgeSet = std::set<std::pair<int, int>>;

/// The edges of `triangles` (the elements of `piece`) that run along one of its lines.
EdgeSet seamEdges(const PointTable& table, const Piece& piece,
                  const std::vector<std::array<int, 3>>& triangles);

}  // namespace rad::meshing
