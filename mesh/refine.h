#pragma once
// Conforming refinement of the patch mesh: longest-edge bisection (Rivara 1984), and the
// check that a mesh has no T-junctions.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "mesh/patch_mesh.h"

namespace rad {

/// Bisects each listed element across its longest edge, first bisecting, in turn, the
/// neighbours along its longest-edge propagation path (LEPP) whose own longest edge is
/// another one, so that every split edge is split on both sides: the mesh stays conforming
/// (no vertex inside another element's edge) and angles stay above half the smallest before.
/// New elements keep their parent's surface, side, patch, base element, materials and normal; each half
/// takes half its parent's area, so patch and surface areas do not change. Elements are only
/// added (existing indices keep their parent's first half); patch element lists, surface
/// element counts and vertex normals are brought up to date. Returns the elements added.
/// `splits`, if given, receives each vertex added and the ends of the edge it halves. No edge
/// shorter than `minEdge` is split: an element whose bisection would need one stays whole.
struct EdgeSplit {
  int vertex = -1, from = -1, to = -1;
};
int bisectElements(PatchMesh& mesh, const std::vector<int>& elements,
                   std::vector<EdgeSplit>* splits = nullptr, double minEdge = 0);

/// The longest edge of element e.
double longestEdge(const PatchMesh& mesh, int e);

/// A key for the edge between vertices a and b, whichever way round.
inline uint64_t edgeKey(int a, int b) {
  return uint64_t(std::min(a, b)) << 32 | uint64_t(std::max(a, b));
}

/// A vertex lying inside an element edge of its own surface side (a T-junction), which a
/// Gouraud display shows as a crack or a seam.
struct TJunction {
  int vertex = -1;
  int edgeFrom = -1, edgeTo = -1;  ///< the edge's end vertices
};

/// Every vertex that lies within `tolerance` (relative to the edge's length) of the inside of
/// an edge of its own surface side without being one of its ends; or two distinct vertices
/// of one surface side at the same point (a crack), unless its elements there bend by more than
/// the crease angle (kCreaseAngleDeg: a box's edge). Empty for a conforming mesh.
/// acrossSurfaces: also vertices of other surfaces inside an edge (where surfaces meet).
std::vector<TJunction> findTJunctions(const PatchMesh& mesh, double tolerance = 1e-7,
                                      bool acrossSurfaces = false);

}  // namespace rad
