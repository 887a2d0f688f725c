// Elements ▸ patches ▸ the PatchMesh: OpenMesh faces with their surface, side, patch, area
// and materials.
#include "mesh/patch_assembly.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_map>

#include <OpenMesh/Core/System/omstream.hh>
#include <glm/geometric.hpp>

#include "mesh/base/progress.h"
#include "mesh/base/union_find.h"
#include "mesh/patch_growth.h"
#include "mesh/scene/geometry.h"
#include "mesh/seams.h"

namespace rad::meshing {
namespace {

/// Elements share a vertex when their normals are within the crease angle.
const double kCreaseCos = std::cos(kCreaseAngleDeg * M_PI / 180.0);

/// A corner of an element: piece, element of the piece, corner (0–2).
struct Corner {
  int piece = -1, element = -1, corner = -1;
};

/// Fills a PatchMesh with the elements of the pieces, patch by patch, one vertex set per
/// surface side; on a seam, one vertex per side of it.
class Assembler {
 public:
  Assembler(const Scene& scene, const PointTable& table, const std::vector<Piece>& pieces,
            const PieceTriangles& elements, const std::vector<EdgeSet>& seams,
            const std::vector<std::vector<std::vector<int>>>& patchesOfPiece, PatchMesh& out)
      : scene_(scene), table_(table), pieces_(pieces), elements_(elements), seams_(seams),
        patchesOfPiece_(patchesOfPiece), sectors_(pieces.size()), out_(out) {}

  /// Adds every side of surface s: its pieces' patches.
  void addSurface(int s, const std::vector<int>& pieces) {
    findSectors(pieces);
    for (int side = 0; side < (scene_.surfaces[size_t(s)].twoSided ? 2 : 1); ++side) addSide(s, side, pieces);
  }

  /// Faces on non-manifold edges that got their own vertices.
  int nonManifold() const { return nonManifold_; }

 private:
  /// Adds one side of surface s, with vertices of its own.
  void addSide(int s, int side, const std::vector<int>& pieces) {
    vertexOf_.clear();
    for (int piece : pieces)
      for (const auto& group : patchesOfPiece_[size_t(piece)]) addPatch(s, side, piece, group);
  }

  /// Whether elements k and l round point p (corners of pieces' elements) meet across an edge
  /// from p that is not a seam.
  bool meetOffSeam(const Corner& k, const Corner& l, int p) const {
    const auto& tk = elements_.triangles[size_t(k.piece)][size_t(k.element)];
    const auto& tl = elements_.triangles[size_t(l.piece)][size_t(l.element)];
    for (int q : tk) {
      if (q == p || std::find(tl.begin(), tl.end(), q) == tl.end()) continue;
      const auto edge = std::minmax(p, q);
      if (!seams_[size_t(k.piece)].count(edge) && !seams_[size_t(l.piece)].count(edge)) return true;
    }
    return false;
  }

  /// The sectors of surface s (its pieces given): round a point on a seam, the elements that
  /// meet across edges other than seams form a sector, which gets a vertex of its own there.
  /// Other corners have sector -1.
  void findSectors(const std::vector<int>& pieces) {
    std::set<int> onSeam;
    for (int piece : pieces)
      for (const auto& [a, b] : seams_[size_t(piece)]) onSeam.insert({a, b});
    if (onSeam.empty()) return;
    std::unordered_map<int, std::vector<Corner>> round;  // per seam point, its elements' corners
    for (int piece : pieces) {
      const auto& triangles = elements_.triangles[size_t(piece)];
      sectors_[size_t(piece)].assign(triangles.size(), {-1, -1, -1});
      for (int k = 0; k < int(triangles.size()); ++k)
        for (int c = 0; c < 3; ++c)
          if (onSeam.count(triangles[size_t(k)][size_t(c)])) round[triangles[size_t(k)][size_t(c)]].push_back({piece, k, c});
    }
    int next = 0;
    for (const auto& [p, corners] : round) {
      UnionFind groups(corners.size());
      for (size_t i = 0; i < corners.size(); ++i)
        for (size_t j = i + 1; j < corners.size(); ++j)
          if (meetOffSeam(corners[i], corners[j], p)) groups.join(i, j);
      for (size_t i = 0; i < corners.size(); ++i)
        sectors_[size_t(corners[i].piece)][size_t(corners[i].element)][size_t(corners[i].corner)] = next + int(groups.find(i));
      next += int(corners.size());
    }
  }

  /// The sectors of the corners of element k of piece `piece` (-1 each off seams).
  std::array<int, 3> sectorsOf(int piece, int k) const {
    const auto& sectors = sectors_[size_t(piece)];
    return sectors.empty() ? std::array<int, 3>{-1, -1, -1} : sectors[size_t(k)];
  }

  /// The vertex of point `id` in `sector` (-1: off seams) on the current surface side for an
  /// element facing `normal`, made when new: elements share a vertex only across edges that
  /// bend less than the crease angle, so light does not smear round a block's edge (a mesh
  /// file's box is one surface), and not across a seam.
  TriMesh::VertexHandle vertex(int id, int sector, const glm::dvec3& normal) {
    auto& atPoint = vertexOf_[int64_t(id) << 32 | int64_t(uint32_t(sector + 1))];
    for (const auto& [v, anchor] : atPoint)
      if (glm::dot(anchor, normal) >= kCreaseCos) return v;
    const auto v = out_.mesh.add_vertex(PatchMesh::toOpenMesh(table_[id]));
    if (sector >= 0) out_.setSeam(v);
    atPoint.push_back({v, normal});
    return v;
  }

  /// The face on points t (ids) in sectors `sector`, sharing the side's vertices; on
  /// non-manifold input (mesh files) a face with its own corners. Vertices are made last
  /// corner first: the numbering results have always had.
  TriMesh::FaceHandle addFace(const std::array<int, 3>& t, const std::array<int, 3>& sector,
                              const glm::dvec3& normal) {
    const auto c = vertex(t[2], sector[2], normal), b = vertex(t[1], sector[1], normal),
               a = vertex(t[0], sector[0], normal);
    auto f = out_.mesh.add_face(a, b, c);
    if (f.is_valid()) return f;
    ++nonManifold_;
    const auto c2 = out_.mesh.add_vertex(PatchMesh::toOpenMesh(table_[t[2]]));
    const auto b2 = out_.mesh.add_vertex(PatchMesh::toOpenMesh(table_[t[1]]));
    const auto a2 = out_.mesh.add_vertex(PatchMesh::toOpenMesh(table_[t[0]]));
    return out_.mesh.add_face(a2, b2, c2);
  }

  /// Adds triangle t (ids, turned for the side) of the patch as an element, unless it has no
  /// area (never after Delaunay refinement; never add zero area).
  void addElement(std::array<int, 3> t, std::array<int, 3> sector, const glm::dvec3& normal, Patch& patch) {
    if (patch.side) std::swap(t[1], t[2]), std::swap(sector[1], sector[2]);
    const glm::dvec3 a = table_[t[0]], b = table_[t[1]], c = table_[t[2]];
    const double area = triangleArea(a, b, c);
    if (!(area > 0)) return;
    const int e = addFace(t, sector, normal).idx();
    setElement(e, patch, area, normal);
    patch.elements.push_back(e);
    patch.area += area;
    patch.centroid += area * (a + b + c) / 3.0;
    noteElement(a, b, c);
  }

  /// Element e's surface, side, area, materials, normal and patch (the one being added).
  void setElement(int e, const Patch& patch, double area, const glm::dvec3& normal) {
    const Material& material = scene_.materials[size_t(scene_.surfaces[size_t(patch.surface)].material)];
    out_.setElement(e, patch.surface, patch.side, area, material.reflectance, material.emission, normal);
    out_.setPatch(e, int(out_.patches.size()));
  }

  /// The smallest angle and longest edge so far, for the stats.
  void noteElement(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    MeshStats& st = out_.stats;
    st.minAngleDeg = std::min({st.minAngleDeg, angleDeg(a, b, c), angleDeg(b, c, a), angleDeg(c, a, b)});
    st.maxEdge = std::max({st.maxEdge, glm::length(b - a), glm::length(c - b), glm::length(a - c)});
  }

  /// Adds the patch of piece `piece` made of its triangles `group` on one side of surface s.
  void addPatch(int s, int side, int piece, const std::vector<int>& group) {
    Patch patch;
    patch.surface = s;
    patch.side = side;
    const glm::dvec3 normal = pieces_[size_t(piece)].frame.normal * (side ? -1.0 : 1.0);
    std::vector<int> points;
    for (int k : group) {
      const auto& t = elements_.triangles[size_t(piece)][size_t(k)];
      points.insert(points.end(), t.begin(), t.end());
      addElement(t, sectorsOf(piece, k), normal, patch);
    }
    if (patch.elements.empty()) return;
    patch.centroid /= patch.area;
    patch.normal = normal;
    patch.diameter = diameter(table_, convexHull(table_, pieces_[size_t(piece)].frame, points));
    countPatch(patch);
    out_.patches.push_back(std::move(patch));
  }

  /// Adds the patch to its surface's totals and the stats.
  void countPatch(const Patch& patch) {
    out_.stats.maxPatchDiameter = std::max(out_.stats.maxPatchDiameter, patch.diameter);
    SurfaceSummary& summary = out_.surfaces[size_t(patch.surface)];
    if (patch.side == 0) summary.area += patch.area;
    summary.elements += int(patch.elements.size());
    summary.patches += 1;
  }

  const Scene& scene_;
  const PointTable& table_;
  const std::vector<Piece>& pieces_;
  const PieceTriangles& elements_;
  const std::vector<EdgeSet>& seams_;  ///< per piece
  const std::vector<std::vector<std::vector<int>>>& patchesOfPiece_;
  /// Per piece of the current surface, per element, its corners' sectors (empty: no seam).
  std::vector<std::vector<std::array<int, 3>>> sectors_;
  PatchMesh& out_;
  /// On the current side: each point's vertices (key: its id and sector), with the normal of
  /// the element that made each.
  std::unordered_map<int64_t, std::vector<std::pair<TriMesh::VertexHandle, glm::dvec3>>> vertexOf_;
  int nonManifold_ = 0;
};

/// The seams of each piece.
std::vector<EdgeSet> seamsOfPieces(const PointTable& table, const std::vector<Piece>& pieces,
                                   const PieceTriangles& elements) {
  std::vector<EdgeSet> seams;
  for (size_t p = 0; p < pieces.size(); ++p) seams.push_back(seamEdges(table, pieces[p], elements.triangles[p]));
  return seams;
}

/// The patches of each piece, as triangle indices.
std::vector<std::vector<std::vector<int>>> patchesOfPieces(const PointTable& table,
                                                           const std::vector<Piece>& pieces,
                                                           const PieceTriangles& elements,
                                                           const std::vector<EdgeSet>& seams,
                                                           double maxPatchEdge) {
  std::vector<std::vector<std::vector<int>>> patches(pieces.size());
  StageProgress progress("patches: pieces", pieces.size());
  for (size_t p = 0; p < pieces.size(); ++p) {
    progress.update(p);
    patches[p] = growPatches(table, pieces[p].frame, elements.triangles[p], seams[p], maxPatchEdge);
  }
  return patches;
}

/// A vertex normal: the area-weighted mean of the adjacent element normals.
OpenMesh::Vec3d vertexNormal(const PatchMesh& out, TriMesh::VertexHandle v) {
  OpenMesh::Vec3d n(0, 0, 0);
  for (auto f : out.mesh.vf_range(v)) n += out.mesh.normal(f) * out.area(f.idx());
  return n.normalized();
}

/// Every vertex's normal.
void setVertexNormals(PatchMesh& out) {
  for (auto v : out.mesh.vertices()) out.mesh.set_normal(v, vertexNormal(out, v));
}

}  // namespace

void assemblePatchMesh(const Scene& scene, const PointTable& table,
                       const std::vector<Piece>& pieces, const PieceTriangles& elements,
                       double maxPatchEdge, PatchMesh& out) {
  auto start = StageTimes::Clock::now();
  const std::vector<EdgeSet> seams = seamsOfPieces(table, pieces, elements);
  const auto patchesOfPiece = patchesOfPieces(table, pieces, elements, seams, maxPatchEdge);
  start = out.stats.stages.add("patches", start);
  std::vector<std::vector<int>> piecesOfSurface(scene.surfaces.size());
  for (size_t p = 0; p < pieces.size(); ++p) piecesOfSurface[size_t(pieces[p].surface)].push_back(int(p));
  Assembler assembler(scene, table, pieces, elements, seams, patchesOfPiece, out);
  // OpenMesh would print "complex edge" for each face it refuses; the count below says it once.
  omerr().disable();
  StageProgress progress("assembly: surfaces", scene.surfaces.size());
  for (size_t s = 0; s < scene.surfaces.size(); ++s) {
    progress.update(s);
    assembler.addSurface(int(s), piecesOfSurface[s]);
  }
  omerr().enable();
  if (assembler.nonManifold())
    out.warnings.push_back("meshing: " + std::to_string(assembler.nonManifold()) +
                           " elements on edges shared by more than two faces (or faces of opposite "
                           "facing) got their own vertices; light is not interpolated across them");
  setVertexNormals(out);
  out.stats.stages.add("assembly", start);
}

}  // namespace rad::meshing
