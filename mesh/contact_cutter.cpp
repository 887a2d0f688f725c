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

#include "mesh/error.h"

namespace rad {
namespace {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using Segments = CGAL::Arr_segment_traits_2<EK>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<Segments, int>;
using Arrangement = CGAL::Arrangement_2<Traits>;
using Face = Arrangement::Face_const_handle;
using Halfedge = Arrangement::Halfedge_const_handle;

/// Curve data: contact lines by index, the polygon's own edges by this.
constexpr int kRingEdge = -1;

EK::Point_2 exact(const glm::dvec2& p) { return {p.x, p.y}; }
glm::dvec2 approx(const EK::Point_2& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

/// Even-odd: inside the polygon's rings.
bool insideRings(const std::vector<std::vector<EK::Point_2>>& rings, const EK::Point_2& q) {
  bool inside = false;
  for (const auto& ring : rings)
    if (CGAL::bounded_side_2(ring.begin(), ring.end(), q, EK()) == CGAL::ON_BOUNDED_SIDE)
      inside = !inside;
  return inside;
}

/// A point strictly inside face f: off the middle of one of its edges, towards the face, by
/// a step (relative to the edge) halved until the point lands in f, by ray-crossing parity
/// against f's boundary cycles.
EK::Point_2 pointIn(Face f) {
  auto try_edge = [&](Halfedge h, EK::Point_2& out) {
    if (h->twin()->face() == f) return false;  // an edge with f on both sides
    EK::Point_2 a = h->source()->point(), b = h->target()->point();
    EK::Point_2 mid = CGAL::midpoint(a, b);
    EK::Vector_2 left = (b - a).perpendicular(CGAL::COUNTERCLOCKWISE);  // f is on the left
    EK::FT step(1.0 / 64);
    for (int k = 0; k < 40; ++k, step /= 2) {
      EK::Point_2 q = mid + left * step;
      // q must lie in f (not only left of this edge: faces need not be convex).
      bool in = true;
      auto check = [&](Arrangement::Ccb_halfedge_const_circulator start) {
        // Ray-crossing parity against the face's boundary cycles.
        auto c = start;
        bool odd = false;
        do {
          EK::Point_2 p0 = c->source()->point(), p1 = c->target()->point();
          if ((p0.y() > q.y()) != (p1.y() > q.y())) {
            EK::FT x = p0.x() + (q.y() - p0.y()) * (p1.x() - p0.x()) / (p1.y() - p0.y());
            if (x > q.x()) odd = !odd;
          }
          if (CGAL::collinear(p0, p1, q) && CGAL::collinear_are_ordered_along_line(p0, q, p1))
            in = false;  // on an edge
        } while (++c != start);
        return odd;
      };
      bool inOuter = f->has_outer_ccb() ? check(f->outer_ccb()) : true;
      bool inHole = false;
      for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole)
        inHole = inHole || check(*hole);
      if (in && inOuter && !inHole) {
        out = q;
        return true;
      }
    }
    return false;
  };
  EK::Point_2 q;
  if (f->has_outer_ccb()) {
    auto c = f->outer_ccb();
    do {
      if (try_edge(c, q)) return q;
    } while (++c != f->outer_ccb());
  }
  for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole) {
    auto c = *hole;
    do {
      if (try_edge(c, q)) return q;
    } while (++c != *hole);
  }
  return f->outer_ccb()->source()->point();  // unreachable for faces of non-zero area
}

/// Signed area of a boundary cycle (counter-clockwise positive); edges walked both ways
/// cancel.
double cycleArea(Arrangement::Ccb_halfedge_const_circulator start) {
  double twice = 0;
  auto c = start;
  do {
    glm::dvec2 a = approx(c->source()->point()), b = approx(c->target()->point());
    twice += a.x * b.y - a.y * b.x;
  } while (++c != start);
  return 0.5 * twice;
}

}  // namespace

ContactCut cutAlongContacts(const Polygon2& polygon, const std::vector<ContactLine2>& contacts) {
  // Exact rings (consecutive duplicates dropped) and the curves of the arrangement.
  std::vector<std::vector<EK::Point_2>> rings;
  std::vector<Traits::Curve_2> curves;
  std::map<std::pair<double, double>, int> idOf;  // points whose id the caller knows
  for (size_t r = 0; r < polygon.rings.size(); ++r) {
    std::vector<EK::Point_2> ring;
    for (size_t k = 0; k < polygon.rings[r].size(); ++k) {
      const glm::dvec2& p = polygon.rings[r][k];
      if (polygon.ids[r][k] >= 0) idOf[{p.x, p.y}] = polygon.ids[r][k];
      if (ring.empty() || ring.back() != exact(p)) ring.push_back(exact(p));
    }
    while (ring.size() > 1 && ring.back() == ring.front()) ring.pop_back();
    for (size_t k = 0; k < ring.size() && ring.size() >= 3; ++k)
      curves.emplace_back(Segments::Curve_2(ring[k], ring[(k + 1) % ring.size()]), kRingEdge);
    rings.push_back(std::move(ring));
  }
  for (size_t i = 0; i < contacts.size(); ++i) {
    const ContactLine2& c = contacts[i];
    if (exact(c.a) == exact(c.b)) continue;
    if (c.aId >= 0) idOf[{c.a.x, c.a.y}] = c.aId;
    if (c.bId >= 0) idOf[{c.b.x, c.b.y}] = c.bId;
    curves.emplace_back(Segments::Curve_2(exact(c.a), exact(c.b)), int(i));
  }
  Arrangement arr;
  CGAL::insert(arr, curves.begin(), curves.end());

  // Which faces lie inside the polygon, and which of those the contacts enclose.
  std::map<Face, bool> kept;
  ContactCut out;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded()) {
      kept[f] = false;
      continue;
    }
    if (!insideRings(rings, pointIn(f))) {
      kept[f] = false;
      continue;
    }
    // An edge closes the face when a contact's solid side faces it, or when it is one of the
    // polygon's edges and some surface stands on it.
    bool closed = true, solid = false;
    std::set<int> enclosing;
    auto visit = [&](Arrangement::Ccb_halfedge_const_circulator start) {
      auto h = start;
      do {
        if (h->twin()->face() == f) continue;  // a line inside the face
        bool ring = false, standing = false, towards = false;
        const glm::dvec2 dir = approx(h->target()->point()) - approx(h->source()->point());
        for (int data : h->curve().data()) {
          if (data == kRingEdge) {
            ring = true;
            continue;
          }
          const ContactLine2& c = contacts[size_t(data)];
          standing = true;
          bool faceOnLeft = glm::dot(dir, c.b - c.a) > 0;  // the face is left of h
          if (c.solid != 0 && (c.solid > 0) == faceOnLeft) {
            towards = true;
            enclosing.insert(data);
          }
        }
        solid = solid || towards;
        closed = closed && (towards || (ring && standing));
      } while (++h != start);
    };
    if (f->has_outer_ccb()) visit(f->outer_ccb());
    for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole) visit(*hole);
    bool hidden = closed && solid;
    kept[f] = !hidden;
    if (hidden) {
      double area = f->has_outer_ccb() ? cycleArea(f->outer_ccb()) : 0;
      for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole)
        area += cycleArea(*hole);  // holes wind clockwise: negative
      out.removed.push_back({area, std::vector<int>(enclosing.begin(), enclosing.end())});
    }
  }

  auto idAt = [&](const EK::Point_2& p) {
    glm::dvec2 q = approx(p);
    auto it = idOf.find({q.x, q.y});
    return it == idOf.end() ? -1 : it->second;
  };
  // Rings: the edges with a kept face on the left and a face left out (or outside) on the
  // right, chained around their end points through the kept faces.
  auto boundary = [&](Halfedge h) { return kept[h->face()] && !kept[h->twin()->face()]; };
  std::set<Halfedge> done;
  for (auto h = arr.halfedges_begin(); h != arr.halfedges_end(); ++h) {
    if (!boundary(h) || done.count(h)) continue;
    std::vector<glm::dvec2> ring;
    std::vector<int> ids;
    std::vector<bool> contact;
    Halfedge e = h;
    do {
      done.insert(e);
      ring.push_back(approx(e->source()->point()));
      ids.push_back(idAt(e->source()->point()));
      const auto& data = e->curve().data();
      contact.push_back(std::find(data.begin(), data.end(), kRingEdge) == data.end());
      Halfedge next = e->next();
      while (!boundary(next)) next = next->twin()->next();
      e = next;
    } while (e != Halfedge(h));
    out.kept.rings.push_back(std::move(ring));
    out.kept.ids.push_back(std::move(ids));
    out.contactEdge.push_back(std::move(contact));
  }
  // Lines: edges with kept faces on both sides (contact lines that cut, or lie inside, what is
  // kept).
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    if (!kept[e->face()] || !kept[e->twin()->face()]) continue;
    out.kept.lines.push_back({approx(e->source()->point()), approx(e->target()->point())});
    out.kept.lineIds.push_back({idAt(e->source()->point()), idAt(e->target()->point())});
  }
  return out;
}

}  // namespace rad
