#pragma once
// Internal to buildPatchMesh: the meshed pieces, grouped into patches, put into the PatchMesh.
#include <vector>

#include "mesh/boundary_agreement.h"
#include "mesh/patch_mesh.h"
#include "mesh/planar_pieces.h"

namespace rad::meshing {

/// Groups each piece's elements into patches no wider than maxPatchEdge and adds them to
/// `out` surface by surface, with one vertex set per surface side (a second, opposite-facing
/// copy for a two-sided surface), their per-surface totals and stats, and the vertex normals.
void assemblePatchMesh(const Scene& scene, const PointTable& table,
                       const std::vector<Piece>& pieces, const PieceTriangles& elements,
                       double maxPatchEdge, PatchMesh& out);

}  // namespace rad::meshing
