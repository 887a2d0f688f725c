// Surfaces ▸ planar pieces ▸ elements ▸ patches: the pipeline of buildPatchMesh, and the
// patch mesh it fills. Each stage has its own file: planar_pieces (surfaces into planar
// pieces), contact_lines (pieces cut where others touch them), boundary_agreement (elements,
// with shared boundary points agreed between neighbours), patch_growth (elements grouped
// into patches) and patch_assembly (all of it into the OpenMesh mesh).
#include "mesh/patch_mesh.h"

#include <algorithm>

#include "mesh/base/error.h"
#include "mesh/boundary_agreement.h"
#include "mesh/contact_lines.h"
#include "mesh/patch_assembly.h"
#include "mesh/planar_pieces.h"

namespace rad {
namespace {

/// Whether some channel is positive.
bool anyPositive(const glm::dvec3& E) { return E.x > 0 || E.y > 0 || E.z > 0; }

}  // namespace

PatchMesh::PatchMesh() {
  mesh.add_property(surface_, "surface");
  mesh.add_property(side_, "side");
  mesh.add_property(patch_, "patch");
  mesh.add_property(base_, "base");
  mesh.add_property(area_, "area");
  mesh.add_property(reflectance_, "reflectance");
  mesh.add_property(emission_, "emission");
  mesh.add_property(seam_, "seam");
}

bool PatchMesh::emits(int p) const {
  const std::vector<int>& elements = patches[size_t(p)].elements;
  return std::any_of(elements.begin(), elements.end(), [&](int e) { return anyPositive(emission(e)); });
}

glm::dvec3 PatchMesh::centroid(int e) const {
  auto c = corners(e);
  return (c[0] + c[1] + c[2]) / 3.0;
}

std::array<glm::dvec3, 3> PatchMesh::corners(int e) const {
  std::array<glm::dvec3, 3> out;
  int k = 0;
  for (auto v : mesh.fv_range(face(e))) out[k++] = toGlm(mesh.point(v));
  return out;
}

void PatchMesh::setElement(int e, int surface, int side, double area,
                           const glm::dvec3& reflectance, const glm::dvec3& emission,
                           const glm::dvec3& normal) {
  auto f = face(e);
  mesh.property(surface_, f) = surface;
  mesh.property(side_, f) = side;
  mesh.property(base_, f) = e;
  mesh.property(area_, f) = area;
  mesh.property(reflectance_, f) = toOpenMesh(reflectance);
  mesh.property(emission_, f) = toOpenMesh(emission);
  mesh.set_normal(f, toOpenMesh(normal));
}

PatchMesh buildPatchMesh(const Scene& scene, const MeshSettings& settings) {
  RAD_CHECK(settings.maxElementEdge > 0);
  RAD_CHECK(settings.maxPatchEdge > 0);
  PatchMesh out;
  out.surfaces.resize(scene.surfaces.size());
  StageTimes& stages = out.stats.stages;
  meshing::PointTable table;
  // Surfaces ▸ planar pieces, cut where other surfaces touch them.
  const auto start = StageTimes::Clock::now();
  std::vector<meshing::Piece> pieces = meshing::planarPieces(scene, table, out.warnings);
  stages.add("planar pieces", start);
  meshing::ContactCuts contacts;
  if (settings.cutContacts) contacts = meshing::cutAtContacts(scene, table, pieces, stages);
  out.cutAway = std::move(contacts.cutAway);
  out.contactLines = contacts.lines;
  // Pieces ▸ elements, neighbours agreeing on the points of shared boundaries.
  const meshing::PieceTriangles elements =
      meshing::meshPieces(scene, settings, table, pieces, contacts.across, stages);
  out.stats.rounds = elements.rounds;
  if (elements.unresolved)
    out.warnings.push_back("meshing: " + std::to_string(elements.unresolved) +
                           " boundary points could not be shared with the neighbouring surface");
  if (elements.leftOut)
    out.warnings.push_back("meshing: " + std::to_string(elements.leftOut) +
                           " faces of mesh files were left out: cut where other objects touch them, their "
                           "outlines crossed themselves (tiny faces of finely tessellated models; light may pass "
                           "through the gaps they leave)");
  // Elements ▸ patches ▸ the OpenMesh mesh.
  meshing::assemblePatchMesh(scene, table, pieces, elements, settings.maxPatchEdge, out);
  return out;
}

}  // namespace rad
