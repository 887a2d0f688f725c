#include "mesh/mesh_export.h"

namespace rad {

PlyMesh toPly(const PatchMesh& m) {
  PlyMesh ply;
  const char* names[] = {"x", "y", "z", "nx", "ny", "nz"};
  for (const char* n : names) ply.vertex.push_back({n, PlyColumn::Type::Float, {}});
  for (auto v : m.mesh.vertices()) {
    const auto& p = m.mesh.point(v);
    const auto& n = m.mesh.normal(v);
    for (int k = 0; k < 3; ++k) {
      ply.vertex[k].values.push_back(p[k]);
      ply.vertex[3 + k].values.push_back(n[k]);
    }
  }
  for (auto f : m.mesh.faces()) {
    std::array<int, 3> idx;
    int k = 0;
    for (auto v : m.mesh.fv_range(f)) idx[k++] = v.idx();
    ply.faces.push_back(idx);
  }
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
