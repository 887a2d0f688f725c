#pragma once
// Internal to buildPatchMesh: the elements of one planar piece grouped into patches.
#include <array>
#include <vector>

#include "mesh/planar_pieces.h"
#include "mesh/scene/geometry.h"
#include "mesh/seams.h"

namespace rad::meshing {

/// The corners of the convex hull of the points (ids), which all lie in `frame`'s plane:
/// Andrew's monotone chain on their projections.
std::vector<int> convexHull(const PointTable& table, const PlaneFrame& frame, std::vector<int> ids);

/// The largest distance between two of the points (ids): between two hull corners.
double diameter(const PointTable& table, const std::vector<int>& hull);

/// Groups the triangles of one planar piece into patches no wider than maxDiameter: each patch
/// grows from the first free triangle in sweep order (along the frame's u axis, then v) to the
/// free edge-neighbours nearest its seed while its diameter allows, so patches are connected
/// and compact; never across a seam (a patch shoots from one point, which must see what all
/// of it sees). Returns triangle indices per patch.
std::vector<std::vector<int>> growPatches(const PointTable& table, const PlaneFrame& frame,
                                          const std::vector<std::array<int, 3>>& triangles,
                                          const EdgeSet& seams, double maxDiameter);

}  // namespace rad::meshing
