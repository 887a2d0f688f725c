#pragma once
// Internal to buildPatchMesh: meshing the planar pieces so that neighbouring pieces agree on
// the points of the boundaries they share.
#include <array>
#include <set>
#include <utility>
#include <vector>

#include "mesh/base/stage_times.h"
#include "mesh/patch_mesh.h"
#include "mesh/planar_pieces.h"

namespace rad::meshing {

/// The elements of every piece as triangles of point ids.
struct PieceTriangles {
  std::vector<std::vector<std::array<int, 3>>> triangles;  ///< per piece
  int rounds = 0;      ///< meshing passes until the pieces agreed
  int unresolved = 0;  ///< boundary points left unshared (agreement gave up)
  int leftOut = 0;     ///< mesh file faces whose cut outline crosses itself, left out
};

/// Meshes every piece with elements no longer than settings.maxElementEdge. Every boundary
/// edge is first cut at the corners of other pieces that lie on it and then into equal parts;
/// the parts are keyed by their end points, so two pieces sharing an edge compute the very
/// same points on it. Edges in `fine` (point id pairs, lower first: contact lines across a
/// piece) are split settings.contactGrading times finer. Refinement may still split a
/// boundary part (encroachment); such points are added to the shared part and its other
/// users are meshed again until all agree. New points go into `table`. Adds the time spent
/// cutting the boundaries ("boundary points"), meshing every piece once ("elements") and
/// meshing again until all agree ("boundary agreement") to `stages`.
PieceTriangles meshPieces(const Scene& scene, const MeshSettings& settings, PointTable& table,
                          const std::vector<Piece>& pieces,
                          const std::set<std::pair<int, int>>& fine, StageTimes& stages);

}  // namespace rad::meshing
