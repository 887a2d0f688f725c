#pragma once
// Reading the binary little-endian triangle PLY files this project writes (and any like them).
#include <string>

#include "mesh/ply_writer.h"

namespace rad {

/// Reads a binary little-endian PLY with a vertex and a triangle face element: every scalar
/// property becomes a column (as double), `vertex_indices` the faces, comments are kept.
/// Throws InputError naming the file and what was expected and found.
PlyMesh readPly(const std::string& path);

/// The column of that name, or nullptr.
const PlyColumn* findColumn(const std::vector<PlyColumn>& columns, const std::string& name);

}  // namespace rad
