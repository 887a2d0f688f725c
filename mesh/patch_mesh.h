#pragma once
// The patch mesh: surfaces ▸ patches (the shooters) ▸ elements (the receivers, triangles).
#include <string>
#include <unordered_map>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <glm/vec3.hpp>

#include "mesh/base/stage_times.h"
#include "mesh/scene/scene.h"

namespace rad {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Normal);
  FaceAttributes(OpenMesh::Attributes::Normal);
};
/// Double precision so that scenes at kilometre or micrometre scale mesh alike.
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

/// Contact lines across a surface (a block's base on a floor) are split into parts this many
/// times shorter than the element edge, and Delaunay refinement grades the elements from
/// there, where the light changes fastest; unless adaptive refinement grades them instead.
constexpr double kDefaultContactGrading = 8;
/// Elements of one surface side share a vertex across an edge that bends by less than this
/// many degrees (the crease angle modelling tools smooth below): a tessellated curve stays
/// smooth, a box's edge keeps a vertex per face, so light does not smear round it (a mesh
/// file's box is one surface), and a polygon triangulated round a slight bend stays smooth.
constexpr double kCreaseAngleDeg = 30;

/// Lengths in scene units.
struct MeshSettings {
  double maxElementEdge = 0;  ///< no element edge is longer
  double maxPatchEdge = 0;    ///< no patch is wider (largest distance between its points)
  bool cutContacts = true;    ///< cut surfaces where others touch them; leave out what they enclose
  double contactGrading = kDefaultContactGrading;  ///< 1: contact lines meshed like the rest
};

/// A shooter: a connected group of elements of one surface side.
struct Patch {
  int surface = -1;
  int side = 0;                ///< 0 front, 1 back (two-sided surfaces)
  std::vector<int> elements;   ///< face indices
  double area = 0;
  glm::dvec3 centroid{0.0};    ///< area-weighted
  glm::dvec3 normal{0.0};      ///< its plane's unit normal, towards the lit side
  double diameter = 0;         ///< largest distance between two of its points
};

/// Per-surface totals.
struct SurfaceSummary {
  double area = 0;  ///< one side
  int elements = 0, patches = 0;
};

/// A part of a surface left out because other surfaces enclose it (the floor under a block):
/// it could neither receive nor send light.
struct CutAway {
  int surface = -1;
  double area = 0;
  std::vector<int> enclosedBy;  ///< the surfaces whose backs face it
};

/// Facts about the meshing, for `radiosity info` and the tests.
struct MeshStats {
  double minAngleDeg = 180, maxEdge = 0, maxPatchDiameter = 0;
  int rounds = 0;  ///< boundary agreement rounds between neighbouring surfaces
  StageTimes stages;  ///< the wall time of each stage of buildPatchMesh
};

/// Elements are the faces of an OpenMesh triangle mesh. Vertices are shared within one side
/// of one surface only; where two surfaces meet, their elements meet at the same points.
class PatchMesh {
 public:
  PatchMesh();

  TriMesh mesh;
  std::vector<Patch> patches;
  std::vector<SurfaceSummary> surfaces;  ///< parallel to Scene::surfaces
  std::vector<CutAway> cutAway;          ///< what contacts left out
  int contactLines = 0;                  ///< lines where surfaces touch, cut into the mesh
  MeshStats stats;
  std::vector<std::string> warnings;     ///< what the mesher changed ("triangulated ...")

  int elementCount() const { return int(mesh.n_faces()); }
  int surface(int e) const { return mesh.property(surface_, face(e)); }
  int side(int e) const { return mesh.property(side_, face(e)); }
  int patch(int e) const { return mesh.property(patch_, face(e)); }
  /// The element of the mesh as built (before refinement) that element e is part of.
  int base(int e) const { return mesh.property(base_, face(e)); }
  double area(int e) const { return mesh.property(area_, face(e)); }
  glm::dvec3 reflectance(int e) const { return toGlm(mesh.property(reflectance_, face(e))); }
  glm::dvec3 emission(int e) const { return toGlm(mesh.property(emission_, face(e))); }
  glm::dvec3 normal(int e) const { return toGlm(mesh.normal(face(e))); }
  glm::dvec3 centroid(int e) const;
  /// Whether vertex v lies on a seam: a contact line across its surface (a wall through a
  /// tread), where each side has vertices of its own, at the same points.
  bool seam(TriMesh::VertexHandle v) const { return mesh.property(seam_, v); }
  void setSeam(TriMesh::VertexHandle v) { mesh.property(seam_, v) = true; }
  /// Whether some element of patch p emits.
  bool emits(int p) const;
  /// The three corners of element e, counter-clockwise seen from its lit side.
  std::array<glm::dvec3, 3> corners(int e) const;
  /// The outline of a group of elements (those for which inGroup(e) holds, `elements`): their
  /// edges with no element of the group on the other side, chained into loops of vertex
  /// indices, counter-clockwise seen from the lit side as the elements are (an outline and,
  /// wound the other way, its holes). Where the group is pinched at a vertex (two boundary
  /// edges leave it), a loop passes it twice. Empty if the edges do not close into loops.
  template <class InGroup>
  std::vector<std::vector<int>> boundaryLoops(const std::vector<int>& elements, const InGroup& inGroup) const;

  /// Sets element e's attributes (its patch stays); used by buildPatchMesh.
  void setElement(int e, int surface, int side, double area, const glm::dvec3& reflectance,
                  const glm::dvec3& emission, const glm::dvec3& normal);
  void setPatch(int e, int patch) { mesh.property(patch_, face(e)) = patch; }
  void setArea(int e, double area) { mesh.property(area_, face(e)) = area; }

  static glm::dvec3 toGlm(const OpenMesh::Vec3d& v) { return {v[0], v[1], v[2]}; }
  static OpenMesh::Vec3d toOpenMesh(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

 private:
  static TriMesh::FaceHandle face(int e) { return TriMesh::FaceHandle(e); }
  OpenMesh::FPropHandleT<int> surface_, side_, patch_, base_;
  OpenMesh::FPropHandleT<double> area_;
  OpenMesh::FPropHandleT<OpenMesh::Vec3d> reflectance_, emission_;
  OpenMesh::VPropHandleT<bool> seam_;
};

template <class InGroup>
std::vector<std::vector<int>> PatchMesh::boundaryLoops(const std::vector<int>& elements, const InGroup& inGroup) const {
  std::unordered_multimap<int, TriMesh::HalfedgeHandle> next;  // from vertex → boundary halfedges
  for (int e : elements)
    for (auto h : mesh.fh_range(face(e))) {
      const auto other = mesh.opposite_face_handle(h);
      if (!other.is_valid() || !inGroup(other.idx())) next.emplace(mesh.from_vertex_handle(h).idx(), h);
    }
  std::vector<std::vector<int>> loops;
  while (!next.empty()) {
    auto at = next.begin();
    const int start = at->first;
    std::vector<int>& loop = loops.emplace_back();
    for (;;) {
      const auto h = at->second;
      next.erase(at);
      loop.push_back(mesh.from_vertex_handle(h).idx());
      const int to = mesh.to_vertex_handle(h).idx();
      if (to == start) break;
      at = next.find(to);
      if (at == next.end()) return {};  // not closed
    }
  }
  return loops;
}

/// Meshes every surface of the scene: planar pieces (non-planar polygons are triangulated,
/// with a warning) are cut along the lines where other surfaces touch or pierce them, and
/// what those surfaces enclose is left out (cutAway); the pieces are refined by Delaunay
/// refinement so that no element edge exceeds settings.maxElementEdge and angles stay above
/// 20.7 degrees where the input allows;
/// neighbouring surfaces are split at the same points along shared edges; elements are then
/// grouped into patches no wider than settings.maxPatchEdge. Two-sided surfaces get a second,
/// opposite-facing copy. Throws InputError for polygons that cannot be meshed.
PatchMesh buildPatchMesh(const Scene& scene, const MeshSettings& settings);

}  // namespace rad
