// Surfaces ▸ planar pieces: each polygon of the scene is one piece, unless it is not planar;
// then it is cut into planar triangles that share their diagonals.
#include "mesh/planar_pieces.h"

#include <algorithm>
#include <cstdio>

namespace rad::meshing {
namespace {

/// A length for messages, to four significant digits.
std::string formatLength(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

/// The ring as point ids, repeated points (also a closing repeat of the first) dropped.
std::vector<int> ringIds(PointTable& table, const Ring& ring) {
  std::vector<int> ids;
  for (const auto& q : ring) {
    int id = table.id(q);
    if (ids.empty() || ids.back() != id) ids.push_back(id);  // drop repeated points
  }
  while (ids.size() > 1 && ids.back() == ids.front()) ids.pop_back();
  return ids;
}

/// The largest distance of a vertex of the polygon (holes too) from the frame's plane.
double planeOffset(const PlaneFrame& frame, const Polygon& polygon) {
  double off = maxPlaneDistance(frame, polygon.outer);
  for (const auto& ring : polygon.holes) off = std::max(off, maxPlaneDistance(frame, ring));
  return off;
}

/// Whether a polygon whose farthest vertex is `off` from its plane counts as planar.
bool isPlanar(double off, const Polygon& polygon) { return off <= kPlanarity * ringDiameter(polygon.outer); }

/// The polygon of surface s as one piece, in the plane of its outer ring.
Piece pieceOf(const Polygon& polygon, int s, bool meshFace, PointTable& table) {
  Piece piece;
  piece.surface = s;
  piece.meshFace = meshFace;
  piece.frame = planeFrame(polygon.outer);
  piece.rings.push_back(ringIds(table, polygon.outer));
  for (const auto& hole : polygon.holes) piece.rings.push_back(ringIds(table, hole));
  return piece;
}

/// A non-planar piece cut into triangles, each planar, sharing their diagonals.
void addTriangles(const Piece& piece, const PointTable& table, const std::string& where,
                  std::vector<Piece>& pieces) {
  Triangulation2 tri = triangulatePolygon(projectedRings(table, piece), where);
  for (const auto& t : tri.triangles) {
    Piece part;
    part.surface = piece.surface;
    part.rings = {{tri.ids[t[0]], tri.ids[t[1]], tri.ids[t[2]]}};
    part.frame = planeFrame({table[part.rings[0][0]], table[part.rings[0][1]],
                             table[part.rings[0][2]]});
    pieces.push_back(std::move(part));
  }
}

/// The warning for `count` triangulated polygons of a surface, the worst `worst` off plane.
std::string nonPlanarWarning(const Surface& surface, int count, double worst) {
  return surface.where + " (" + surface.name + "): " + std::to_string(count) +
         " non-planar polygon(s) triangulated into planar triangles (a vertex lies " +
         formatLength(worst) + " off the best-fit plane)";
}

/// Adds the pieces of surface s; warns about the polygons that had to be triangulated.
void addSurfacePieces(const Surface& surface, int s, PointTable& table,
                      std::vector<Piece>& pieces, std::vector<std::string>& warnings) {
  int triangulated = 0;
  double worst = 0;
  for (const auto& polygon : surface.polygons) {
    Piece piece = pieceOf(polygon, s, surface.fromMeshFile, table);
    const double off = planeOffset(piece.frame, polygon);
    if (isPlanar(off, polygon)) {
      pieces.push_back(std::move(piece));
      continue;
    }
    addTriangles(piece, table, surface.where, pieces);
    ++triangulated;
    worst = std::max(worst, off);
  }
  if (triangulated) warnings.push_back(nonPlanarWarning(surface, triangulated, worst));
}

}  // namespace

Polygon2 projectedRings(const PointTable& table, const Piece& piece) {
  Polygon2 poly;
  for (const auto& ring : piece.rings) {
    poly.rings.emplace_back();
    for (int id : ring) poly.rings.back().push_back(piece.frame.project(table[id]));
    poly.ids.push_back(ring);
  }
  return poly;
}

std::vector<Piece> planarPieces(const Scene& scene, PointTable& table,
                                std::vector<std::string>& warnings) {
  std::vector<Piece> pieces;
  for (size_t s = 0; s < scene.surfaces.size(); ++s)
    addSurfacePieces(scene.surfaces[s], int(s), table, pieces, warnings);
  return pieces;
}

}  // namespace rad::meshing
