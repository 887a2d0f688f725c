#pragma once
// Triangulation and quality meshing of planar polygons with holes, in the polygon's own
// 2D frame. The CGAL implementation stays behind this header.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

namespace rad {

/// A polygon in 2D: closed rings, inside by the even-odd rule (rings[0] is usually the outer
/// boundary, the rest holes); ids[r][k] names rings[r][k] for the caller (a shared boundary
/// point), or is -1. `lines` are open polylines inside it that meshing must keep as edges
/// (contact lines), with their ids alike.
struct Polygon2 {
  std::vector<std::vector<glm::dvec2>> rings;
  std::vector<std::vector<int>> ids;
  std::vector<std::vector<glm::dvec2>> lines;
  std::vector<std::vector<int>> lineIds;
};

/// A triangulation of a Polygon2. Triangles are counter-clockwise; points keep the
/// caller's ids, and points the mesher added have id -1.
struct Triangulation2 {
  std::vector<glm::dvec2> points;
  std::vector<int> ids;
  std::vector<bool> onBoundary;  ///< added points that lie on a boundary segment
  std::vector<std::array<int, 3>> triangles;
};

/// The smallest angle Delaunay refinement guarantees away from small input angles.
constexpr double kMeshMinAngleDeg = 20.7;

/// Constrained Delaunay triangulation of the polygon, no points added.
/// Throws InputError(where ...) if the rings cross each other or themselves.
Triangulation2 triangulatePolygon(const Polygon2& polygon, const std::string& where);

/// Delaunay refinement: every triangle has edges no longer than maxEdge and angles of at
/// least kMeshMinAngleDeg wherever the input's angles allow. Boundary segments may be split;
/// the added points are flagged onBoundary. A lone triangle of a mesh file (meshFace) within
/// maxEdge is kept as it is, whatever its angles; a larger one is split by its congruent
/// lattice, unless it is large and well shaped (a wall drawn as two triangles), which is
/// meshed like a polygon. A polygon whose refinement would make more than `maxVertices`
/// vertices (0: refinementBudget of the polygon) is a sliver, and is meshed as it is: its
/// constrained triangulation, a triangle longer than maxEdge split by the points of its
/// congruent lattice, no point added on its boundary.
Triangulation2 meshPolygon(const Polygon2& polygon, double maxEdge, const std::string& where,
                           bool meshFace = false, size_t maxVertices = 0);

/// Whether the polygon's outline fits within one element: no two of its points farther apart
/// than maxEdge. A mesh file's small face, cut where another object touches it, is then
/// meshed as it is; refined for shape, its neighbours' points and its own passed back and
/// forth until a staircase's brass fittings had twenty elements per face.
bool withinElement(const Polygon2& polygon, double maxEdge);

/// The polygon meshed as it is: its constrained triangulation, each triangle longer than
/// maxEdge split by the points of its congruent lattice, no point added on its boundary, no
/// refinement for shape. For surfaces whose elements' shape shows nothing (black ones).
Triangulation2 meshPolygonAsIs(const Polygon2& polygon, double maxEdge, const std::string& where);

/// The vertices Delaunay refinement may make of the polygon before it counts as a sliver: a
/// multiple of those of an equilateral mesh of its area at maxEdge and of its boundary
/// points and lines.
size_t refinementBudget(const Polygon2& polygon, double maxEdge);

}  // namespace rad
