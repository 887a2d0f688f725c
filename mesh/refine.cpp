#include "mesh/refine.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "mesh/base/error.h"
#include "mesh/base/spatial_hash.h"

namespace rad {
namespace {

using Mesh = TriMesh;

/// The squared length of edge e, computed from its ends in index order so that both of its
/// faces see the same value (the longest-edge order must be one order).
double squaredLength(const Mesh& m, Mesh::EdgeHandle e) {
  auto h = m.halfedge_handle(e, 0);
  auto a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
  if (b.idx() < a.idx()) std::swap(a, b);
  return (m.point(b) - m.point(a)).sqrnorm();
}

/// The longest edge of f; ties go to the smaller edge index, so that the order is total and
/// the propagation path ends.
Mesh::EdgeHandle longest(const Mesh& m, Mesh::FaceHandle f) {
  Mesh::EdgeHandle best;
  double most = -1;
  for (auto h : m.fh_range(f)) {
    auto e = m.edge_handle(h);
    double l = squaredLength(m, e);
    if (l > most || (l == most && e.idx() < best.idx())) most = l, best = e;
  }
  return best;
}

/// Whether f is flat, its corners on one line to rounding (height over its longest edge below
/// kFlatHeight): halving such an element makes more of them, without end, and no light to see.
constexpr double kFlatHeight = 1e-9;
bool flat(const Mesh& m, Mesh::FaceHandle f) {
  auto h = m.halfedge_handle(f);
  const auto a = m.point(m.from_vertex_handle(h)), b = m.point(m.to_vertex_handle(h)),
             c = m.point(m.to_vertex_handle(m.next_halfedge_handle(h)));
  const double twiceArea = ((b - a) % (c - a)).norm();
  const double longest2 = std::max({(b - a).sqrnorm(), (c - b).sqrnorm(), (a - c).sqrnorm()});
  return twiceArea <= kFlatHeight * longest2;
}

/// The mean length of the mesh's edges (0 without edges).
double meanEdgeLength(const Mesh& m) {
  double sum = 0;
  for (auto e : m.edges()) sum += std::sqrt(squaredLength(m, e));
  return sum / double(std::max<size_t>(1, m.n_edges()));
}

/// Each vertex's surface side (surface * 2 + side), -1 for a vertex of no element.
std::vector<int> vertexSides(const PatchMesh& pm) {
  std::vector<int> side(pm.mesh.n_vertices(), -1);
  for (auto v : pm.mesh.vertices())
    for (auto f : pm.mesh.vf_range(v)) {
      side[size_t(v.idx())] = pm.surface(f.idx()) * 2 + pm.side(f.idx());
      break;
    }
  return side;
}

/// The vertices in a hash of cells of size `cell`.
SpatialHash vertexHash(const Mesh& m, double cell) {
  SpatialHash grid(cell);
  for (auto v : m.vertices()) grid.insert(PatchMesh::toGlm(m.point(v)), v.idx());
  return grid;
}

/// Whether coincident vertices v and w of one side are meant apart: their elements bend by
/// more than the crease angle (kCreaseAngleDeg), so each face of a box keeps its own.
bool acrossCrease(const Mesh& m, Mesh::VertexHandle v, Mesh::VertexHandle w) {
  return (m.normal(v) | m.normal(w)) < std::cos(kCreaseAngleDeg * M_PI / 180.0);
}

/// Adds the vertices of v's side in v's cell (after v) within `distance` of it, apart from
/// those meant apart: across a crease, or the two sides of a seam.
void addCoincident(const PatchMesh& pm, const SpatialHash& grid, const std::vector<int>& side,
                   Mesh::VertexHandle v, double distance, std::vector<TJunction>& out) {
  const Mesh& m = pm.mesh;
  const glm::dvec3 p = PatchMesh::toGlm(m.point(v));
  grid.visit(p, p, [&](int w) {
    if (w <= v.idx() || side[size_t(w)] != side[size_t(v.idx())] || acrossCrease(m, v, Mesh::VertexHandle(w))) return;
    if (pm.seam(v) && pm.seam(Mesh::VertexHandle(w))) return;
    if ((m.point(Mesh::VertexHandle(w)) - m.point(v)).norm() <= distance)
      out.push_back({w, v.idx(), v.idx()});
  });
}

/// Adds the vertices (of the edge's side, when `side` is given) inside edge e: within
/// `tolerance` of it, relative to its length, and not near its ends.
void addInsideEdge(const Mesh& m, const SpatialHash& grid, const std::vector<int>* side,
                   Mesh::EdgeHandle e, double tolerance, std::vector<TJunction>& out) {
  auto h = m.halfedge_handle(e, 0);
  auto a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
  const auto pa = m.point(a), pb = m.point(b);
  const auto d = pb - pa;
  const double len2 = d.sqrnorm();
  if (!(len2 > 0)) return;
  const glm::dvec3 ga = PatchMesh::toGlm(pa), gb = PatchMesh::toGlm(pb);
  grid.visit(glm::min(ga, gb), glm::max(ga, gb), [&](int w) {
    if (w == a.idx() || w == b.idx() || (side && (*side)[size_t(w)] != (*side)[size_t(a.idx())])) return;
    const auto pw = m.point(Mesh::VertexHandle(w));
    const double t = ((pw - pa) | d) / len2;
    if (t <= tolerance || t >= 1 - tolerance) return;
    const double off = (pw - (pa + d * t)).norm();
    if (off <= tolerance * std::sqrt(len2)) out.push_back({w, a.idx(), b.idx()});
  });
}

/// Exact positions, bit for bit: where surfaces meet, their vertices were made from the same
/// points, and midpoints of equal ends are equal.
struct PositionHash {
  size_t operator()(const OpenMesh::Vec3d& p) const {
    std::hash<double> h;
    return h(p[0]) ^ (h(p[1]) * 0x9e3779b97f4a7c15ull) ^ (h(p[2]) * 0xc2b2ae3d27d4eb4full);
  }
};

class Bisector {
 public:
  Bisector(PatchMesh& mesh, std::vector<EdgeSplit>* splits, double minEdge)
      : pm_(mesh), m_(mesh.mesh), splits_(splits), minSquared_(minEdge * minEdge) {
    for (auto v : m_.vertices()) at_.emplace(m_.point(v), v.idx());
  }

  /// Bisects f across its longest edge, after its LEPP neighbours as needed; false, f left
  /// as it is, when an element on the way is flat or an edge too short to halve (shorter than
  /// the floor, or a rounding step long).
  bool bisect(Mesh::FaceHandle f) {
    for (;;) {
      if (flat(m_, f)) return false;
      auto e = longest(m_, f);
      auto g = across(f, e);
      if (!g.is_valid() || longest(m_, g) == e) return split(e);
      if (!bisect(g)) return false;  // f's neighbour across e is now one half of g: look again
    }
  }

  int added() const { return added_; }

 private:
  /// The element beside f across its edge e (invalid on a boundary).
  Mesh::FaceHandle across(Mesh::FaceHandle f, Mesh::EdgeHandle e) const {
    auto h = m_.halfedge_handle(e, 0);
    return m_.face_handle(h) == f ? m_.opposite_face_handle(h) : m_.face_handle(h);
  }

  /// An element beside h whose longest edge is another one (the second if both), or none.
  Mesh::FaceHandle sideWithLongerEdge(Mesh::HalfedgeHandle h) const {
    Mesh::FaceHandle shorter;
    for (Mesh::FaceHandle f : {Mesh::FaceHandle(m_.face_handle(h)), Mesh::FaceHandle(m_.opposite_face_handle(h))})
      if (f.is_valid() && longest(m_, f) != m_.edge_handle(h)) shorter = f;
    return shorter;
  }

  /// Splits the edge from a to b at its midpoint, bisecting the element beside it until that
  /// edge is its longest (within its surface side, conformingly as ever).
  void splitEdgeBetween(Mesh::VertexHandle a, Mesh::VertexHandle b) {
    for (;;) {
      auto h = m_.find_halfedge(a, b);
      if (!h.is_valid()) return;  // split already
      auto e = m_.edge_handle(h);
      // Both elements beside the edge must have it as their longest, or the split would cut
      // one across a shorter edge (and break the angle bound).
      const Mesh::FaceHandle shorter = sideWithLongerEdge(h);
      if (!shorter.is_valid()) {
        split(e);
        return;
      }
      if (!bisect(shorter)) return;
    }
  }

  /// Where an edge is split, the edges of other surfaces (or of faces with their own
  /// corners) between the same two points are split too: no T-junction where surfaces meet
  /// (a wall on a floor, a board along a line across it), no crack for light to leak through.
  void splitTwins(Mesh::VertexHandle a, Mesh::VertexHandle b) {
    for (auto [a2, b2] : twinsOf(a, b)) splitEdgeBetween(a2, b2);
  }

  /// The other edges between the points of a and b (vertices of other surfaces at them, or the
  /// other side's of a seam).
  std::vector<std::pair<Mesh::VertexHandle, Mesh::VertexHandle>> twinsOf(Mesh::VertexHandle a,
                                                                          Mesh::VertexHandle b) const {
    std::vector<std::pair<Mesh::VertexHandle, Mesh::VertexHandle>> twins;
    const auto pb = m_.point(b);
    auto [lo, hi] = at_.equal_range(m_.point(a));
    for (auto it = lo; it != hi; ++it) {
      Mesh::VertexHandle a2(it->second);
      // Either end may be the same vertex: where a seam ends inside a surface, its last
      // vertex is both sides' own.
      for (auto b2 : m_.vv_range(a2))
        if ((a2 != a || b2 != b) && m_.point(b2) == pb) twins.emplace_back(a2, b2);
    }
    return twins;
  }

  /// The faces on either side of h, which keep their handles as one half, with their areas
  /// halved.
  std::vector<std::pair<Mesh::FaceHandle, double>> halvedAreas(Mesh::HalfedgeHandle h) const {
    std::vector<std::pair<Mesh::FaceHandle, double>> halved;
    for (auto side : {h, m_.opposite_halfedge_handle(h)}) {
      auto f = m_.face_handle(side);
      if (f.is_valid()) halved.emplace_back(f, pm_.area(f.idx()) * 0.5);
    }
    return halved;
  }

  /// The normal of a new vertex on the edge from a to b: it lies on the edge, so it takes
  /// the edge's mean normal.
  OpenMesh::Vec3d edgeNormal(Mesh::VertexHandle a, Mesh::VertexHandle b) const {
    auto n = m_.normal(a) + m_.normal(b);
    return n.norm() > 0 ? n.normalized() : n;
  }

  /// Splits edge e at its midpoint (and the same edge of other surfaces: splitTwins); false,
  /// nothing split, when e is shorter than the floor, an element beside it is flat, or its
  /// midpoint rounds to an end. Without these, a fan of flat slivers (where meshing cut a
  /// cornice's end to a line, its corners micrometres apart) was halved down to rounding
  /// steps: thousands of vertices on one point, minutes, and the stack's end.
  bool split(Mesh::EdgeHandle e) {
    if (squaredLength(m_, e) < minSquared_) return false;
    auto h = m_.halfedge_handle(e, 0);
    for (auto side : {h, m_.opposite_halfedge_handle(h)})
      if (m_.face_handle(side).is_valid() && flat(m_, m_.face_handle(side))) return false;
    const auto a = m_.from_vertex_handle(h), b = m_.to_vertex_handle(h);  // before the split
    const auto mid = (m_.point(a) + m_.point(b)) * 0.5;
    if (mid == m_.point(a) || mid == m_.point(b)) return false;
    const auto halved = halvedAreas(h);
    const bool onSeam = pm_.seam(a) && pm_.seam(b) && m_.is_boundary(e);
    const size_t facesBefore = m_.n_faces();
    auto v = m_.add_vertex(mid);
    if (onSeam) pm_.setSeam(v);
    if (splits_) splits_->push_back({v.idx(), a.idx(), b.idx()});
    m_.split_copy(e, v);  // the new faces copy their parent's properties
    for (auto& [f, area] : halved) pm_.setArea(f.idx(), area);
    // The new faces are the parents' other halves: they copied the parent's area.
    for (size_t k = facesBefore; k < m_.n_faces(); ++k) pm_.setArea(int(k), pm_.area(int(k)) * 0.5);
    added_ += int(m_.n_faces() - facesBefore);
    m_.set_normal(v, edgeNormal(a, b));
    at_.emplace(mid, v.idx());
    splitTwins(a, b);
    return true;
  }

  PatchMesh& pm_;
  Mesh& m_;
  std::vector<EdgeSplit>* splits_;
  double minSquared_;  // edges shorter than the floor, squared, are left whole
  std::unordered_multimap<OpenMesh::Vec3d, int, PositionHash> at_;  // vertices by position
  int added_ = 0;
};

/// Patch element lists and surface element counts, from the elements.
void recountElements(PatchMesh& mesh) {
  for (auto& p : mesh.patches) p.elements.clear();
  for (auto& s : mesh.surfaces) s.elements = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) {
    mesh.patches[size_t(mesh.patch(e))].elements.push_back(e);
    mesh.surfaces[size_t(mesh.surface(e))].elements += 1;
  }
}

}  // namespace

double longestEdge(const PatchMesh& mesh, int e) {
  return std::sqrt(squaredLength(mesh.mesh, longest(mesh.mesh, Mesh::FaceHandle(e))));
}

int bisectElements(PatchMesh& mesh, const std::vector<int>& elements, std::vector<EdgeSplit>* splits,
                   double minEdge) {
  const int before = mesh.elementCount();
  Bisector bisector(mesh, splits, minEdge);
  // An element listed may already have been halved by a neighbour's propagation path; it is
  // bisected once more all the same: what was asked is that it get smaller.
  for (int e : elements) {
    RAD_CHECK(e >= 0 && e < before);
    bisector.bisect(Mesh::FaceHandle(e));
  }
  recountElements(mesh);
  return mesh.elementCount() - before;
}

std::vector<TJunction> findTJunctions(const PatchMesh& pm, double tolerance, bool acrossSurfaces) {
  const Mesh& m = pm.mesh;
  std::vector<TJunction> out;
  if (m.n_vertices() == 0) return out;
  // Vertices by surface side, in a hash of cells about one mean edge wide.
  const double meanEdge = meanEdgeLength(m);
  const double cell = meanEdge > 0 ? meanEdge : 1.0;
  const std::vector<int> side = vertexSides(pm);
  const SpatialHash grid = vertexHash(m, cell);
  // Coincident vertices of one side.
  for (auto v : m.vertices()) addCoincident(pm, grid, side, v, tolerance * cell, out);
  // Vertices inside edges: visit the cells the edge's bounding box covers.
  for (auto e : m.edges())
    addInsideEdge(m, grid, acrossSurfaces ? nullptr : &side, e, tolerance, out);
  return out;
}

}  // namespace rad
