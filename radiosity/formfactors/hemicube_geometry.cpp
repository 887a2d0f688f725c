// Patch mesh ▸ the triangles a hemicube draws, and which of them have a twin side in place.
#include <algorithm>

#include <glm/geometric.hpp>

#include "mesh/patch_mesh.h"
#include "radiosity/formfactors/hemicube.h"

namespace rad {

HemicubeGeometry HemicubeGeometry::fromMesh(const PatchMesh& mesh) {
  HemicubeGeometry g;
  for (auto v : mesh.mesh.vertices()) g.positions.push_back(PatchMesh::toGlm(mesh.mesh.point(v)));
  for (auto f : mesh.mesh.faces()) {
    for (auto v : mesh.mesh.fv_range(f)) g.indices.push_back(uint32_t(v.idx()));
    g.normals.push_back(mesh.normal(f.idx()));
  }
  std::vector<int> surfaceOf(size_t(mesh.elementCount()));
  for (int e = 0; e < mesh.elementCount(); ++e) surfaceOf[size_t(e)] = mesh.surface(e);
  g.markTwoSided(mesh, surfaceOf);
  return g;
}

void HemicubeGeometry::markTwoSided(const PatchMesh& mesh, const std::vector<int>& surfaceOf) {
  // A surface is two-sided when some of its elements lie on its second side.
  std::vector<uint8_t> twoSidedSurface(mesh.surfaces.size(), 0);
  for (int e = 0; e < mesh.elementCount(); ++e) twoSidedSurface[size_t(mesh.surface(e))] |= uint8_t(mesh.side(e) == 1);
  twoSided.clear();
  if (std::find(twoSidedSurface.begin(), twoSidedSurface.end(), 1) == twoSidedSurface.end()) return;
  for (int s : surfaceOf) twoSided.push_back(twoSidedSurface[size_t(s)]);
}

int HemicubeGeometry::addTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  uint32_t base = uint32_t(positions.size());
  positions.insert(positions.end(), {a, b, c});
  indices.insert(indices.end(), {base, base + 1, base + 2});
  normals.push_back(glm::normalize(glm::cross(b - a, c - a)));
  return int(normals.size()) - 1;
}

}  // namespace rad
