#pragma once
// A binary little-endian PLY writer for triangle meshes with per-vertex and per-face
// properties (the result-mesh contract of DESIGN.md).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rad {

/// One scalar property column: its PLY type and one value per vertex or face.
struct PlyColumn {
  enum class Type { Float, Int, UChar };
  std::string name;
  Type type;
  std::vector<double> values;
};

struct PlyMesh {
  std::vector<std::string> comments;
  std::vector<PlyColumn> vertex;               ///< x, y, z first, then any others
  std::vector<std::array<int, 3>> faces;       ///< vertex indices
  std::vector<PlyColumn> face;                 ///< written after vertex_indices
};

/// Writes the mesh atomically (temporary file, then rename). Throws InputError on failure.
void writePly(const std::string& path, const PlyMesh& mesh);

}  // namespace rad
