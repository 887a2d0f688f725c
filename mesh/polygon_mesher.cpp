// CGAL's constrained Delaunay triangulation and Delaunay refinement (Mesh_2).
#include "mesh/polygon_mesher.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <string>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/base/error.h"
#include "mesh/scene/geometry.h"

namespace rad {
namespace {

/// A mesh file's triangle at least this many element edges long, with no angle below
/// kLargeFaceMinAngleDeg, is meshed as a scene polygon (isLargeWellShaped).
constexpr double kLargeFaceEdges = 3;
constexpr double kLargeFaceMinAngleDeg = 30;
constexpr double kLargeFaceMinSegment = 0.125;
/// Delaunay refinement that would make more vertices than this many times an equilateral
/// mesh's of the polygon (its area at the element edge, and its boundary points) is meeting a
/// sliver (a thin face of a downloaded model, 5 m by 2 mm, cut by a contact line): refined
/// for shape it would fill with ~(length / width)² tiny elements and pass boundary points on
/// to its neighbours, who refine in turn. Such a polygon is meshed as it is (meshAsIs).
constexpr double kRefinementBudget = 16;
/// ...plus this many vertices, so that a small polygon's few are never a sliver's.
constexpr size_t kRefinementSlack = 64;
/// Refinement steps (points tried, accepted or not) allowed per vertex of the budget: near
/// nearly coincident constraints of a downloaded model, CGAL's mesher can try and reject
/// points without end (a staircase's piece looped for minutes, inserting none).
constexpr size_t kRefinementStepsPerVertex = 16;

struct PointId {
  int id = -1;
};

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<PointId, K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
using Face = CDT::Face_handle;

/// The rings' constraint edges, as vertex pairs (lower first).
using RingEdges = std::set<std::pair<CDT::Vertex_handle, CDT::Vertex_handle>>;

/// Inserts the points; a point's id is the caller's, unless it has one already and the
/// caller's is -1.
std::vector<CDT::Vertex_handle> insertPoints(CDT& cdt, const std::vector<glm::dvec2>& points,
                                             const std::vector<int>& ids) {
  std::vector<CDT::Vertex_handle> vs;
  for (size_t k = 0; k < points.size(); ++k) {
    auto v = cdt.insert(K::Point_2(points[k].x, points[k].y));
    if (ids[k] >= 0 || v->info().id < 0) v->info().id = ids[k];
    vs.push_back(v);
  }
  return vs;
}

/// Inserts the points as a chain of constraints, closed for a ring (whose edges go into
/// ringEdges). A point's id is the caller's, unless another chain gave it one already.
void insertChain(CDT& cdt, const std::vector<glm::dvec2>& points, const std::vector<int>& ids,
                 bool closed, RingEdges& ringEdges) {
  const std::vector<CDT::Vertex_handle> vs = insertPoints(cdt, points, ids);
  for (size_t k = 0; k + (closed ? 0 : 1) < vs.size(); ++k) {
    auto a = vs[k], b = vs[(k + 1) % vs.size()];
    if (a == b) continue;
    cdt.insert_constraint(a, b);
    if (closed) ringEdges.insert({std::min(a, b), std::max(a, b)});
  }
}

/// Inserts every ring as a closed chain of constraints and every line as an open one; returns
/// the rings' edges.
RingEdges insertRings(CDT& cdt, const Polygon2& polygon, const std::string& where) {
  RingEdges ringEdges;
  try {
    for (size_t r = 0; r < polygon.rings.size(); ++r)
      insertChain(cdt, polygon.rings[r], polygon.ids[r], true, ringEdges);
    for (size_t l = 0; l < polygon.lines.size(); ++l)
      insertChain(cdt, polygon.lines[l], polygon.lineIds[l], false, ringEdges);
  } catch (const CDT::Intersection_of_constraints_exception&) {
    throw inputError(where, "a simple polygon whose holes lie inside it",
                     "edges that cross each other");
  }
  return ringEdges;
}

/// insertRings, but a polygon whose contact lines cross each other (interpenetrating parts
/// of one downloaded model, a lamp's disk pierced by the finely tessellated holder round it)
/// is meshed without them rather than refusing the scene: the lines are the contacts' doing,
/// not the user's.
RingEdges insertFaceRings(CDT& cdt, const Polygon2& polygon, const std::string& where) {
  if (polygon.lines.empty()) return insertRings(cdt, polygon, where);
  try {
    return insertRings(cdt, polygon, where);
  } catch (const InputError&) {
    Polygon2 ringsOnly = polygon;
    ringsOnly.lines.clear();
    ringsOnly.lineIds.clear();
    cdt.clear();
    return insertRings(cdt, ringsOnly, where);
  }
}

/// Whether edge i of face f (opposite its vertex i) is an edge of a ring.
bool isRingEdge(const RingEdges& ringEdges, Face f, int i) {
  auto a = f->vertex(CDT::cw(i)), b = f->vertex(CDT::ccw(i));
  return ringEdges.count({std::min(a, b), std::max(a, b)}) > 0;
}

/// Each face's nesting depth across the rings' constraints (the lines inside do not count),
/// breadth-first from the infinite face, one nesting level at a time.
std::map<Face, int> nestingDepth(const CDT& cdt, const RingEdges& ringEdges) {
  std::map<Face, int> depth;
  std::queue<Face> frontier, next;
  next.push(cdt.infinite_face());
  depth[cdt.infinite_face()] = 0;
  for (int level = 0; !next.empty(); ++level) {
    std::swap(frontier, next);
    while (!frontier.empty()) {
      Face f = frontier.front();
      frontier.pop();
      for (int i = 0; i < 3; ++i) {
        Face g = f->neighbor(i);
        if (depth.count(g)) continue;
        const bool deeper = isRingEdge(ringEdges, f, i);
        depth[g] = level + (deeper ? 1 : 0);
        (deeper ? next : frontier).push(g);
      }
    }
  }
  return depth;
}

/// Marks f's connected part of the inside seen, parts being split by any constraint.
void markPart(const CDT& cdt, Face f, std::map<Face, bool>& seen) {
  std::queue<Face> q;
  q.push(f);
  seen[f] = true;
  while (!q.empty()) {
    Face g = q.front();
    q.pop();
    for (int i = 0; i < 3; ++i) {
      Face h = g->neighbor(i);
      if (cdt.is_infinite(h) || seen[h] || cdt.is_constrained(CDT::Edge(g, i))) continue;
      if (h->is_in_domain()) {
        seen[h] = true;
        q.push(h);
      }
    }
  }
}

/// Marks faces by nesting depth across the rings' constraints (odd = inside the polygon minus
/// its holes; the lines inside do not count) and returns one seed point in each connected part
/// of the inside, parts being split by any constraint.
std::vector<K::Point_2> markInside(CDT& cdt, const RingEdges& ringEdges) {
  std::map<Face, int> depth = nestingDepth(cdt, ringEdges);
  for (auto f : cdt.finite_face_handles()) f->set_in_domain(depth[f] % 2 == 1);
  std::vector<K::Point_2> seeds;
  std::map<Face, bool> seen;
  for (auto f : cdt.finite_face_handles()) {
    if (!f->is_in_domain() || seen[f]) continue;
    seeds.push_back(CGAL::centroid(cdt.triangle(f)));
    markPart(cdt, f, seen);
  }
  return seeds;
}

/// Whether a constraint (a boundary segment or a line) ends at v.
bool onConstraint(const CDT& cdt, CDT::Vertex_handle v) {
  bool constrained = false;
  auto e = cdt.incident_edges(v), end = e;
  do {
    constrained = constrained || cdt.is_constrained(*e);
  } while (++e != end);
  return constrained;
}

/// The triangulation's points (with their ids) and its faces inside the domain.
Triangulation2 extract(const CDT& cdt) {
  Triangulation2 out;
  std::map<CDT::Vertex_handle, int> index;
  for (auto v : cdt.finite_vertex_handles()) {
    index[v] = int(out.points.size());
    out.points.emplace_back(v->point().x(), v->point().y());
    out.ids.push_back(v->info().id);
    out.onBoundary.push_back(v->info().id < 0 && onConstraint(cdt, v));
  }
  for (auto f : cdt.finite_face_handles())
    if (f->is_in_domain())
      out.triangles.push_back({index[f->vertex(0)], index[f->vertex(1)], index[f->vertex(2)]});
  return out;
}

/// The angle at a of the triangle a, b, c (radians).
double angleAt(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  glm::dvec2 u = b - a, v = c - a;
  return std::atan2(std::abs(u.x * v.y - u.y * v.x), u.x * v.x + u.y * v.y);
}

/// Whether a, b, c turn counter-clockwise.
bool turnsLeft(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) > 0;
}

/// A lone triangle that needs no CGAL at all: no longer than maxEdge and, unless it is a face
/// of a mesh file, with no angle below the bound. A mesh file's thin faces are kept as they
/// are: refining them for shape only fills them with tiny elements (a UV sphere's poles took
/// minutes, or overflowed the stack).
bool isGoodTriangle(const Polygon2& p, double maxEdge, bool meshFace) {
  if (p.rings.size() != 1 || p.rings[0].size() != 3 || !p.lines.empty()) return false;
  const auto& r = p.rings[0];
  const double lo = kMeshMinAngleDeg * M_PI / 180, hi = M_PI / 2;  // obtuse: encroached
  for (int i = 0; i < 3; ++i) {
    double a = angleAt(r[i], r[(i + 1) % 3], r[(i + 2) % 3]);
    double len = std::hypot(r[i].x - r[(i + 1) % 3].x, r[i].y - r[(i + 1) % 3].y);
    if (len > maxEdge || (!meshFace && (a < lo || a > hi))) return false;
  }
  return turnsLeft(r[0], r[1], r[2]);
}

/// The polygon, a lone triangle, as its own triangulation.
Triangulation2 loneTriangle(const Polygon2& p) {
  Triangulation2 out;
  out.points = p.rings[0];
  out.ids = p.ids[0];
  out.onBoundary.assign(3, false);
  out.triangles.push_back({0, 1, 2});
  return out;
}

/// The points where the ring turns (its corners, without the points along its edges).
std::vector<glm::dvec2> turningPoints(const std::vector<glm::dvec2>& ring) {
  std::vector<glm::dvec2> corners;
  const size_t n = ring.size();
  for (size_t k = 0; k < n; ++k) {
    const glm::dvec2 &a = ring[(k + n - 1) % n], &b = ring[k], &c = ring[(k + 1) % n];
    const glm::dvec2 u = b - a, v = c - b;
    const double cross = u.x * v.y - u.y * v.x;
    if (std::abs(cross) > 1e-9 * std::hypot(u.x, u.y) * std::hypot(v.x, v.y)) corners.push_back(b);
  }
  return corners;
}

/// Whether the polygon is one ring that turns at three points: a mesh file's triangle, its
/// edges cut at the points agreed with its neighbours (and perhaps contact lines across it).
bool isTriangleFace(const Polygon2& p) {
  return p.rings.size() == 1 && turningPoints(p.rings[0]).size() == 3;
}

/// Whether q lies at least `clearance` from every line of the polygon.
bool clearOfLines(const Polygon2& p, const glm::dvec2& q, double clearance) {
  for (const auto& line : p.lines)
    for (size_t k = 0; k + 1 < line.size(); ++k)
      if (segmentDistance(q, line[k], line[k + 1]) < clearance) return false;
  return true;
}

/// The inside points of the m×m congruent split of triangle t that keep clear of the
/// polygon's lines by a third of the split's edge (none for m < 3).
std::vector<glm::dvec2> latticeInside(const Polygon2& p, const std::vector<glm::dvec2>& t, int m, double edge) {
  std::vector<glm::dvec2> out;
  for (int i = 1; i < m; ++i)
    for (int j = 1; i + j < m; ++j) {
      const glm::dvec2 q = (double(i) * t[0] + double(j) * t[1] + double(m - i - j) * t[2]) / double(m);
      if (clearOfLines(p, q, edge / (3 * m))) out.push_back(q);
    }
  return out;
}

/// A mesh file's triangle: its boundary points as agreed with its neighbours, its contact lines
/// and the inside points of its m×m congruent split (m from its longest edge), triangulated as
/// they are. No Delaunay refinement: refining a mesh file's thin faces splits their edges, which
/// splits their neighbours' in turn, without end (a water surface of 10 000 faces did so until
/// the points were 1e-12 apart).
Triangulation2 meshTriangleFace(const Polygon2& polygon, double maxEdge, const std::string& where) {
  const std::vector<glm::dvec2> t = turningPoints(polygon.rings[0]);
  const double longest = std::max({glm::length(t[1] - t[0]), glm::length(t[2] - t[1]), glm::length(t[0] - t[2])});
  const int m = int(std::ceil(longest / maxEdge));
  CDT cdt;
  RingEdges ringEdges = insertFaceRings(cdt, polygon, where);
  for (const glm::dvec2& q : latticeInside(polygon, t, m, longest)) cdt.insert(K::Point_2(q.x, q.y));
  markInside(cdt, ringEdges);
  return extract(cdt);
}

/// The shortest segment of a ring (closed).
double shortestSegment(const std::vector<glm::dvec2>& ring) {
  double shortest = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < ring.size(); ++k) shortest = std::min(shortest, glm::length(ring[(k + 1) % ring.size()] - ring[k]));
  return shortest;
}

/// Whether a mesh file's triangle is a wall or floor drawn as triangles, to be meshed as a
/// scene polygon would be, so that the same room meshes alike from any format: large (three
/// element edges or more across), well shaped (no angle below kLargeFaceMinAngleDeg), and
/// with no boundary point its neighbours put close to another (shortest segment at least
/// kLargeFaceMinSegment element edges; below, refinement for shape would grade down to it,
/// as along the rim of a water surface of 10 000 faces).
bool isLargeWellShaped(const Polygon2& polygon, double maxEdge) {
  const std::vector<glm::dvec2> t = turningPoints(polygon.rings[0]);
  double longest = 0;
  for (int i = 0; i < 3; ++i) {
    if (angleAt(t[size_t(i)], t[size_t(i + 1) % 3], t[size_t(i + 2) % 3]) < kLargeFaceMinAngleDeg * M_PI / 180) return false;
    longest = std::max(longest, glm::length(t[size_t(i + 1) % 3] - t[size_t(i)]));
  }
  return longest >= kLargeFaceEdges * maxEdge && shortestSegment(polygon.rings[0]) >= kLargeFaceMinSegment * maxEdge;
}

/// Delaunay refinement of the marked domain of `cdt` (one seed per part): elements no longer
/// than maxEdge, angles of at least kMeshMinAngleDeg where the input allows. False, the
/// refinement left unfinished, once the triangulation has more than maxVertices vertices or
/// the steps are more than kRefinementStepsPerVertex times that.
bool refineWithin(CDT& cdt, const std::vector<K::Point_2>& seeds, double maxEdge, size_t maxVertices) {
  // Shape bound 0.125 is CGAL's default, the 20.7 degree guarantee of Delaunay refinement.
  CGAL::Delaunay_mesher_2<CDT, Criteria> mesher(cdt, Criteria(0.125, maxEdge));
  mesher.set_seeds(seeds.begin(), seeds.end(), true);
  mesher.init();
  for (size_t steps = 1; mesher.try_one_step_refine_mesh(); ++steps)
    if (cdt.number_of_vertices() > maxVertices || steps > kRefinementStepsPerVertex * maxVertices) return false;
  return true;
}

/// The lattice points (latticeInside) of every triangle of the domain longer than maxEdge.
std::vector<glm::dvec2> latticePoints(const CDT& cdt, const Polygon2& polygon, double maxEdge) {
  std::vector<glm::dvec2> points;
  for (auto f : cdt.finite_face_handles()) {
    if (!f->is_in_domain()) continue;
    std::vector<glm::dvec2> t;
    for (int i = 0; i < 3; ++i) t.emplace_back(f->vertex(i)->point().x(), f->vertex(i)->point().y());
    const double longest = std::max({glm::length(t[1] - t[0]), glm::length(t[2] - t[1]), glm::length(t[0] - t[2])});
    const int m = int(std::ceil(longest / maxEdge));
    for (const glm::dvec2& q : latticeInside(polygon, t, m, longest)) points.push_back(q);
  }
  return points;
}

}  // namespace

bool withinElement(const Polygon2& polygon, double maxEdge) {
  glm::dvec2 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const glm::dvec2& q : polygon.rings[0]) lo = glm::min(lo, q), hi = glm::max(hi, q);
  if (glm::length(hi - lo) <= maxEdge) return true;  // the box's diagonal bounds the diameter
  const std::vector<glm::dvec2>& ring = polygon.rings[0];
  for (size_t i = 0; i < ring.size(); ++i)
    for (size_t j = i + 1; j < ring.size(); ++j)
      if (glm::length(ring[j] - ring[i]) > maxEdge) return false;
  return true;
}

namespace {

/// The polygon's constrained triangulation (rings and lines inserted as `ringEdges`), each
/// triangle longer than maxEdge given the inside points of its congruent split, no point
/// added on the boundary: a sliver's elements are as thin as it is, but no more numerous.
Triangulation2 meshAsIs(CDT& cdt, const RingEdges& ringEdges, const Polygon2& polygon, double maxEdge) {
  markInside(cdt, ringEdges);
  for (const glm::dvec2& q : latticePoints(cdt, polygon, maxEdge)) cdt.insert(K::Point_2(q.x, q.y));
  markInside(cdt, ringEdges);
  return extract(cdt);
}

}  // namespace

size_t refinementBudget(const Polygon2& polygon, double maxEdge) {
  double area = 0, points = 0;
  for (const auto& ring : polygon.rings) {
    points += double(ring.size());
    for (size_t k = 0; k < ring.size(); ++k) area += ring[k].x * ring[(k + 1) % ring.size()].y - ring[(k + 1) % ring.size()].x * ring[k].y;
  }
  for (const auto& line : polygon.lines) points += double(line.size());
  const double equilateral = std::sqrt(3.0) / 4 * maxEdge * maxEdge;
  return size_t(kRefinementBudget * (std::abs(area) / 2 / equilateral + points)) + kRefinementSlack;
}

Triangulation2 triangulatePolygon(const Polygon2& polygon, const std::string& where) {
  CDT cdt;
  markInside(cdt, insertRings(cdt, polygon, where));
  return extract(cdt);
}

Triangulation2 meshPolygonAsIs(const Polygon2& polygon, double maxEdge, const std::string& where) {
  CDT cdt;
  const RingEdges ringEdges = insertFaceRings(cdt, polygon, where);
  return meshAsIs(cdt, ringEdges, polygon, maxEdge);
}

Triangulation2 meshPolygon(const Polygon2& polygon, double maxEdge, const std::string& where,
                           bool meshFace, size_t maxVertices) {
  if (isGoodTriangle(polygon, maxEdge, meshFace)) return loneTriangle(polygon);
  if (meshFace && isTriangleFace(polygon) && !isLargeWellShaped(polygon, maxEdge))
    return meshTriangleFace(polygon, maxEdge, where);
  CDT cdt;
  const RingEdges ringEdges = insertFaceRings(cdt, polygon, where);
  if (meshFace && withinElement(polygon, maxEdge)) return meshAsIs(cdt, ringEdges, polygon, maxEdge);
  const std::vector<K::Point_2> seeds = markInside(cdt, ringEdges);
  if (refineWithin(cdt, seeds, maxEdge, maxVertices ? maxVertices : refinementBudget(polygon, maxEdge)))
    return extract(cdt);
  // A sliver: refined for shape it would fill with tiny elements. Meshed as it is instead.
  cdt.clear();
  return meshAsIs(cdt, insertFaceRings(cdt, polygon, where), polygon, maxEdge);
}

}  // namespace rad
