#pragma once
// Reading PLY files: the binary little-endian triangle results this project writes, and PLY
// meshes of polygons in any of the three formats. Every count, size, index and number is
// checked before use; an error names the file, the element and record, and what was found.
#include <string>
#include <vector>

#include "mesh/base/ply_writer.h"

namespace rad {

/// Longest face (vertices) a PLY may hold.
constexpr size_t kMaxPlyFaceVertices = 1024;

/// Reads a binary little-endian PLY with a vertex and a triangle face element: every scalar
/// property becomes a column (as double), `vertex_indices` the faces, comments are kept.
/// Throws InputError naming the file and what was expected and found.
PlyMesh readPly(const std::string& path);

/// A PLY mesh of polygons: the vertex and face elements' scalar properties as columns (mesh.faces
/// stays empty) and each face's vertex indices.
struct PlyPolygons {
  PlyMesh mesh;
  std::vector<std::vector<int>> faces;
};

/// Reads a PLY in ascii, binary_little_endian or binary_big_endian format whose faces may
/// have any number of vertices (3 to kMaxPlyFaceVertices).
PlyPolygons readPlyPolygons(const std::string& path);

/// The column of that name, or nullptr.
const PlyColumn* findColumn(const std::vector<PlyColumn>& columns, const std::string& name);

}  // namespace rad
