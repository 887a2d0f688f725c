// CGAL's 2D arrangements with exact constructions: the polygon's rings and the contact lines
// cut the plane into faces; each face is kept, left out (enclosed by what touches it), or
// outside the polygon.
#include "mesh/contact_cutter.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <glm/geometric.hpp>

#include "mesh/base/error.h"

namespace rad {
namespace {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using Segments = CGAL::Arr_segment_traits_2<EK>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<Segments, int>;
using Arrangement = CGAL::Arrangement_2<Traits>;
using Face = Arrangement::Face_const_handle;
using Halfedge = Arrangement::Halfedge_const_handle;
using Ccb = Arrangement::Ccb_halfedge_const_circulator;  ///< a boundary cycle of a face
/// Where the caller's ids are known, by position.
using IdMap = std::map<std::pair<double, double>, int>;
/// Whether each face of the arrangement is kept.
using KeptFaces = std::map<Face, bool>;

/// Curve data: contact lines by index, the polygon's own edges by these: an edge it shares with
/// a face of its own surface in its plane (inner: a floor's diagonal), or any other.
constexpr int kRingEdge = -1;
constexpr int kInnerEdge = -2;

/// The point as an exact one, and back (rounded).
EK::Point_2 exact(const glm::dvec2& p) { return {p.x, p.y}; }
glm::dvec2 approx(const EK::Point_2& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

/// Even-odd: inside the polygon's rings.
bool insideRings(const std::vector<std::vector<EK::Point_2>>& rings, const EK::Point_2& q) {
  return std::count_if(rings.begin(), rings.end(), [&](const auto& ring) {
           return CGAL::bounded_side_2(ring.begin(), ring.end(), q, EK()) == CGAL::ON_BOUNDED_SIDE;
         }) % 2 == 1;
}

/// Calls f on each boundary cycle of face `face`: its outer one (if any), then its holes.
template <class F>
void forEachCycle(Face face, F&& f) {
  if (face->has_outer_ccb()) f(face->outer_ccb());
  for (auto hole = face->inner_ccbs_begin(); hole != face->inner_ccbs_end(); ++hole) f(*hole);
}

/// Whether the edge from p0 to p1 crosses the ray from q along +x.
bool crossesRay(const EK::Point_2& p0, const EK::Point_2& p1, const EK::Point_2& q) {
  if ((p0.y() > q.y()) == (p1.y() > q.y())) return false;
  return p0.x() + (q.y() - p0.y()) * (p1.x() - p0.x()) / (p1.y() - p0.y()) > q.x();
}

/// Ray-crossing parity of q against one boundary cycle: true when odd. Sets `onEdge` when q
/// lies on one of the cycle's edges.
bool oddCrossings(Ccb start, const EK::Point_2& q, bool& onEdge) {
  auto c = start;
  bool odd = false;
  do {
    EK::Point_2 p0 = c->source()->point(), p1 = c->target()->point();
    if (crossesRay(p0, p1, q)) odd = !odd;
    if (CGAL::collinear(p0, p1, q) && CGAL::collinear_are_ordered_along_line(p0, q, p1))
      onEdge = true;
  } while (++c != start);
  return odd;
}

/// Whether q lies in face f, on none of its edges (faces need not be convex).
bool strictlyInside(Face f, const EK::Point_2& q) {
  bool onEdge = false;
  bool inOuter = f->has_outer_ccb() ? oddCrossings(f->outer_ccb(), q, onEdge) : true;
  bool inHole = false;
  for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole)
    inHole = inHole || oddCrossings(*hole, q, onEdge);
  return !onEdge && inOuter && !inHole;
}

/// A point of face f off the middle of its edge h, towards f (on h's left), by a step
/// (relative to the edge) halved until the point lands in f; false when none does or f lies
/// on both sides of h.
bool pointBeside(Face f, Halfedge h, EK::Point_2& out) {
  if (h->twin()->face() == f) return false;  // an edge with f on both sides
  EK::Point_2 a = h->source()->point(), b = h->target()->point();
  EK::Point_2 mid = CGAL::midpoint(a, b);
  EK::Vector_2 left = (b - a).perpendicular(CGAL::COUNTERCLOCKWISE);  // f is on the left
  EK::FT step(1.0 / 64);
  for (int k = 0; k < 40; ++k, step /= 2) {
    out = mid + left * step;
    if (strictlyInside(f, out)) return true;
  }
  return false;
}

/// A point of face f beside one of the edges of the cycle, the first that gives one.
bool pointBesideCycle(Face f, Ccb start, EK::Point_2& q) {
  auto c = start;
  do {
    if (pointBeside(f, c, q)) return true;
  } while (++c != start);
  return false;
}

/// A point strictly inside face f: beside one of its edges, outer boundary first.
EK::Point_2 pointIn(Face f) {
  EK::Point_2 q;
  bool found = false;
  forEachCycle(f, [&](Ccb c) { found = found || pointBesideCycle(f, c, q); });
  return found ? q : f->outer_ccb()->source()->point();  // unreachable for faces of non-zero area
}

/// Signed area of a boundary cycle (counter-clockwise positive); edges walked both ways
/// cancel.
double cycleArea(Ccb start) {
  double twice = 0;
  auto c = start;
  do {
    glm::dvec2 a = approx(c->source()->point()), b = approx(c->target()->point());
    twice += a.x * b.y - a.y * b.x;
  } while (++c != start);
  return 0.5 * twice;
}

/// The area of face f: its outer cycle less its holes.
double faceArea(Face f) {
  double area = 0;
  forEachCycle(f, [&](Ccb c) { area += cycleArea(c); });  // holes wind clockwise: negative
  return area;
}

/// Notes the caller's id of point p, if it has one.
void noteId(IdMap& idOf, const glm::dvec2& p, int id) {
  if (id >= 0) idOf[{p.x, p.y}] = id;
}

/// Ring r of the polygon in exact points, consecutive duplicates dropped; the ids it knows go
/// into idOf.
std::vector<EK::Point_2> exactRing(const Polygon2& polygon, size_t r, IdMap& idOf) {
  std::vector<EK::Point_2> ring;
  for (size_t k = 0; k < polygon.rings[r].size(); ++k) {
    const glm::dvec2& p = polygon.rings[r][k];
    noteId(idOf, p, polygon.ids[r][k]);
    if (ring.empty() || ring.back() != exact(p)) ring.push_back(exact(p));
  }
  while (ring.size() > 1 && ring.back() == ring.front()) ring.pop_back();
  return ring;
}

/// Ring r's edges as curves (none for fewer than three points), inner ones (`inner`: id pairs,
/// lower first) marked so.
void addRingCurves(const Polygon2& polygon, size_t r, size_t points, const std::set<std::pair<int, int>>& inner,
                   std::vector<Traits::Curve_2>& curves) {
  if (points < 3) return;
  const auto& ring = polygon.rings[r];
  const auto& ids = polygon.ids[r];
  for (size_t k = 0; k < ring.size(); ++k) {
    const size_t next = (k + 1) % ring.size();
    if (exact(ring[k]) == exact(ring[next])) continue;
    const bool isInner = ids[k] >= 0 && ids[next] >= 0 && inner.count(std::minmax(ids[k], ids[next]));
    curves.emplace_back(Segments::Curve_2(exact(ring[k]), exact(ring[next])), isInner ? kInnerEdge : kRingEdge);
  }
}

/// The contact lines as curves, with their indices as data (points apart); their ends' ids
/// go into idOf.
void addContactCurves(const std::vector<ContactLine2>& contacts, IdMap& idOf,
                      std::vector<Traits::Curve_2>& curves) {
  for (size_t i = 0; i < contacts.size(); ++i) {
    const ContactLine2& c = contacts[i];
    if (exact(c.a) == exact(c.b)) continue;
    noteId(idOf, c.a, c.aId);
    noteId(idOf, c.b, c.bId);
    curves.emplace_back(Segments::Curve_2(exact(c.a), exact(c.b)), int(i));
  }
}

/// How the edges around a face close it.
struct Enclosure {
  bool closed = true;  ///< every edge closes it
  bool solid = false;  ///< some contact's solid side faces it
  std::set<int> by;  ///< contacts whose solid side faces f
  std::set<int> covers;  ///< cover lines round it
};

/// Whether contact c, which runs along h, has its solid side towards h's face (on h's left).
bool solidTowards(Halfedge h, const ContactLine2& c) {
  const glm::dvec2 dir = approx(h->target()->point()) - approx(h->source()->point());
  bool faceOnLeft = glm::dot(dir, c.b - c.a) > 0;  // the face is left of h
  return c.solid != 0 && (c.solid > 0) == faceOnLeft;
}

/// Notes the edges of one boundary cycle of f: an edge closes the face when a contact's
/// solid side faces it, or when it is one of the polygon's edges and some surface stands on
/// it.
void noteCycle(Face f, Ccb start, const std::vector<ContactLine2>& contacts, Enclosure& e) {
  auto h = start;
  do {
    if (h->twin()->face() == f) continue;  // a line inside the face
    bool ring = false, inner = false, standing = false, towards = false;
    for (int data : h->curve().data()) {
      ring = ring || data < 0;
      inner = inner || data == kInnerEdge;
      if (data < 0) continue;
      if (contacts[size_t(data)].cover) {
        e.covers.insert(data);
        continue;
      }
      standing = true;
      if (solidTowards(h, contacts[size_t(data)])) towards = true, e.by.insert(data);
    }
    e.solid = e.solid || towards;
    e.closed = e.closed && (towards || (ring && standing) || inner);
  } while (++h != start);
}

/// How the contacts enclose face f.
Enclosure enclosureOf(Face f, const std::vector<ContactLine2>& contacts) {
  Enclosure e;
  forEachCycle(f, [&](Ccb c) { noteCycle(f, c, contacts, e); });
  return e;
}

/// The area centroid of a boundary cycle.
glm::dvec2 cycleCentroid(Ccb start) {
  glm::dvec2 sum(0.0);
  double twice = 0;
  auto c = start;
  do {
    glm::dvec2 a = approx(c->source()->point()), b = approx(c->target()->point());
    const double cross = a.x * b.y - a.y * b.x;
    sum += (a + b) * cross, twice += cross;
  } while (++c != start);
  return twice != 0 ? sum / (3 * twice) : approx(start->source()->point());
}

/// A point well inside face f, away from its edges where it can be: the centroid of its outer
/// boundary when that lies in f (a footprint, a strip), else a point beside an edge.
glm::dvec2 deepPointIn(Face f) {
  if (f->has_outer_ccb()) {
    const glm::dvec2 c = cycleCentroid(f->outer_ccb());
    if (strictlyInside(f, exact(c))) return c;
  }
  return approx(pointIn(f));
}

/// Which faces lie inside the polygon and are kept; those the contacts enclose and that lie
/// inside a solid are left out and recorded in `removed`.
KeptFaces classifyFaces(const Arrangement& arr, const std::vector<std::vector<EK::Point_2>>& rings,
                        const std::vector<ContactLine2>& contacts, const InsideSolid& insideSolid,
                        const InsideSolid& covered, std::vector<ContactCut::Removed>& removed) {
  const bool covers = covered && std::any_of(contacts.begin(), contacts.end(), [](const auto& c) { return c.cover; });
  KeptFaces kept;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded() || !insideRings(rings, pointIn(f))) {
      kept[f] = false;
      continue;
    }
    const Enclosure e = enclosureOf(f, contacts);
    if (covers && covered(deepPointIn(f))) {  // under a surface lying on this one
      kept[f] = false;
      removed.push_back({faceArea(f), std::vector<int>(e.covers.begin(), e.covers.end())});
      continue;
    }
    const bool hidden = e.closed && e.solid && insideSolid(deepPointIn(f));
    kept[f] = !hidden;
    if (hidden) removed.push_back({faceArea(f), std::vector<int>(e.by.begin(), e.by.end())});
  }
  return kept;
}

/// The caller's id of point p, or -1.
int idAt(const IdMap& idOf, const EK::Point_2& p) {
  glm::dvec2 q = approx(p);
  auto it = idOf.find({q.x, q.y});
  return it == idOf.end() ? -1 : it->second;
}

/// Whether h bounds what is kept: a kept face on its left, a face left out (or outside) on
/// its right.
bool keptBoundary(KeptFaces& kept, Halfedge h) { return kept[h->face()] && !kept[h->twin()->face()]; }

/// Whether h runs along contact lines only (none of the polygon's own edges).
bool isContactEdge(Halfedge h) {
  const auto& data = h->curve().data();
  return std::none_of(data.begin(), data.end(), [](int d) { return d < 0; });
}

/// The kept boundary edge after e, around e's target through the kept faces.
Halfedge nextKeptBoundary(KeptFaces& kept, Halfedge e) {
  Halfedge next = e->next();
  while (!keptBoundary(kept, next)) next = next->twin()->next();
  return next;
}

/// Adds the ring of kept boundary edges through h, chained around their end points through
/// the kept faces, to out; marks its edges done.
void addKeptRing(KeptFaces& kept, const IdMap& idOf, Halfedge h, std::set<Halfedge>& done,
                 ContactCut& out) {
  std::vector<glm::dvec2> ring;
  std::vector<int> ids;
  std::vector<bool> contact;
  Halfedge e = h;
  do {
    done.insert(e);
    ring.push_back(approx(e->source()->point()));
    ids.push_back(idAt(idOf, e->source()->point()));
    contact.push_back(isContactEdge(e));
    e = nextKeptBoundary(kept, e);
  } while (e != h);
  out.kept.rings.push_back(std::move(ring));
  out.kept.ids.push_back(std::move(ids));
  out.contactEdge.push_back(std::move(contact));
}

/// Rings: the boundaries of what is kept.
void addKeptRings(const Arrangement& arr, KeptFaces& kept, const IdMap& idOf, ContactCut& out) {
  std::set<Halfedge> done;
  for (auto h = arr.halfedges_begin(); h != arr.halfedges_end(); ++h)
    if (keptBoundary(kept, h) && !done.count(h)) addKeptRing(kept, idOf, h, done, out);
}

/// Lines: edges with kept faces on both sides (contact lines that cut, or lie inside, what is
/// kept).
void addKeptLines(const Arrangement& arr, KeptFaces& kept, const IdMap& idOf, ContactCut& out) {
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    if (!kept[e->face()] || !kept[e->twin()->face()]) continue;
    out.kept.lines.push_back({approx(e->source()->point()), approx(e->target()->point())});
    out.kept.lineIds.push_back({idAt(idOf, e->source()->point()), idAt(idOf, e->target()->point())});
  }
}

}  // namespace

ContactCut cutAlongContacts(const Polygon2& polygon, const std::vector<ContactLine2>& contacts,
                            const InsideSolid& insideSolid, const InsideSolid& covered,
                            const std::set<std::pair<int, int>>& innerEdges) {
  // Exact rings (consecutive duplicates dropped) and the curves of the arrangement.
  IdMap idOf;  // points whose id the caller knows
  std::vector<std::vector<EK::Point_2>> rings;
  std::vector<Traits::Curve_2> curves;
  for (size_t r = 0; r < polygon.rings.size(); ++r) {
    rings.push_back(exactRing(polygon, r, idOf));
    addRingCurves(polygon, r, rings.back().size(), innerEdges, curves);
  }
  addContactCurves(contacts, idOf, curves);
  Arrangement arr;
  CGAL::insert(arr, curves.begin(), curves.end());
  // Which faces lie inside the polygon, and which of those the contacts enclose in a solid.
  ContactCut out;
  KeptFaces kept = classifyFaces(arr, rings, contacts, insideSolid, covered, out.removed);
  // What is kept: its boundary rings, and the lines inside it.
  addKeptRings(arr, kept, idOf, out);
  addKeptLines(arr, kept, idOf, out);
  return out;
}

}  // namespace rad
