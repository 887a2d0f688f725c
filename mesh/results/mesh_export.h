#pragma once
// The patch mesh as PLY columns: positions, normals, faces and their surface index.
#include "mesh/base/ply_writer.h"
#include "mesh/patch_mesh.h"

namespace rad {

/// Vertex x y z nx ny nz, face vertex_indices and int surface; callers append their own
/// columns (patch index, colours, radiosity) in the order their contract lists them.
PlyMesh toPly(const PatchMesh& mesh);

/// One column of per-face integers (e.g. the patch index).
PlyColumn faceIntColumn(const PatchMesh& mesh, const std::string& name, int (PatchMesh::*get)(int) const);

}  // namespace rad
