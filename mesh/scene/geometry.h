#pragma once
// Small geometric helpers on GLM double vectors: polygon normals, areas, plane frames.
#include <array>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mesh/scene/scene.h"

namespace rad {

/// Polygons smaller than this times their diameter squared count as zero-area.
constexpr double kMinRelativeArea = 1e-12;
/// Points farther than this times the polygon's diameter from its plane make it non-planar.
constexpr double kPlanarity = 1e-6;

/// Newell's normal of a closed ring: its direction follows the right-hand rule, its length
/// is twice the (projected) area enclosed.
glm::dvec3 newellNormal(const Ring& ring);

/// An orthonormal frame on a polygon's plane: normal by the right-hand rule.
struct PlaneFrame {
  glm::dvec3 origin, u, v, normal;
  glm::dvec2 project(const glm::dvec3& p) const;
  glm::dvec3 lift(const glm::dvec2& q) const;
};

/// The frame of the best-fit plane of a ring (Newell normal, origin at the centroid of
/// its vertices).
PlaneFrame planeFrame(const Ring& ring);
/// The frame of the plane through `origin` with unit normal `normal`.
PlaneFrame planeFrame(const glm::dvec3& origin, const glm::dvec3& normal);

/// The convex hull of points in a plane: the indices of its corners, counter-clockwise
/// (Andrew's monotone chain on the points sorted by x, then y; points on its edges left out).
/// Fewer than three points: all of them.
std::vector<size_t> convexHull(const std::vector<glm::dvec2>& points);

/// Area of a triangle in 3D.
double triangleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

/// The angle at a of triangle a, b, c, in degrees.
double angleDeg(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

/// Triangle t cut into m² congruent triangles (each edge into m equal pieces), with t's
/// orientation.
std::vector<std::array<glm::dvec3, 3>> congruentSplit(const std::array<glm::dvec3, 3>& t, int m);

/// The area of a planar polygon minus its holes (projected onto its best-fit plane).
double polygonArea(const Polygon& polygon);

/// The median of the values (the upper one of an even count); HUGE_VAL when there are none.
double median(std::vector<double> values);

/// The largest distance between two vertices of a ring.
double ringDiameter(const Ring& ring);

/// The largest distance of a vertex of the ring from the frame's plane.
double maxPlaneDistance(const PlaneFrame& frame, const Ring& ring);

/// The distance from q to the segment from a to b (a != b).
double segmentDistance(const glm::dvec2& q, const glm::dvec2& a, const glm::dvec2& b);

/// Whether p, projected onto the frame's plane, lies strictly inside the projected ring.
bool insideRing(const PlaneFrame& frame, const Ring& ring, const glm::dvec3& p);

/// Whether p, on the frame's plane, lies inside the polygon: even-odd over its outer ring and
/// its holes.
bool insidePolygon(const PlaneFrame& frame, const Polygon& polygon, const glm::dvec3& p);

}  // namespace rad
