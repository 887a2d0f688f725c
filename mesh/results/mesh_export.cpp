#include "mesh/results/mesh_export.h"

namespace rad {
namespace {

/// The vertices' positions and normals as columns x, y, z, nx, ny, nz.
std::vector<PlyColumn> vertexColumns(const PatchMesh& m) {
  std::vector<PlyColumn> columns;
  for (const char* n : {"x", "y", "z", "nx", "ny", "nz"}) columns.push_back({n, PlyColumn::Type::Float, {}});
  for (auto v : m.mesh.vertices()) {
    const auto& p = m.mesh.point(v);
    const auto& n = m.mesh.normal(v);
    for (int k = 0; k < 3; ++k) {
      columns[k].values.push_back(p[k]);
      columns[3 + k].values.push_back(n[k]);
    }
  }
  return columns;
}

/// Element e's corners (vertex indices).
std::array<int, 3> cornerIds(const PatchMesh& m, int e) {
  std::array<int, 3> idx;
  int k = 0;
  for (auto v : m.mesh.fv_range(TriMesh::FaceHandle(e))) idx[k++] = v.idx();
  return idx;
}

/// Each element's corners (vertex indices).
std::vector<std::array<int, 3>> elementCorners(const PatchMesh& m) {
  std::vector<std::array<int, 3>> faces;
  for (int e = 0; e < m.elementCount(); ++e) faces.push_back(cornerIds(m, e));
  return faces;
}

}  // namespace

PlyMesh toPly(const PatchMesh& m) {
  PlyMesh ply;
  ply.vertex = vertexColumns(m);
  ply.faces = elementCorners(m);
  ply.face.push_back(faceIntColumn(m, "surface", &PatchMesh::surface));
  return ply;
}

PlyColumn faceIntColumn(const PatchMesh& m, const std::string& name,
                        int (PatchMesh::*get)(int) const) {
  PlyColumn c{name, PlyColumn::Type::Int, {}};
  for (int e = 0; e < m.elementCount(); ++e) c.values.push_back((m.*get)(e));
  return c;
}

}  // namespace rad
