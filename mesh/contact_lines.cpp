// Planar pieces ▸ pieces cut along contact lines, with what the contacts enclose left out.
#include "mesh/contact_lines.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "mesh/base/progress.h"
#include "mesh/base/spatial_hash.h"
#include "mesh/contact_cutter.h"
#include "mesh/coplanar_pieces.h"
#include "mesh/piece_boxes.h"
#include "mesh/scene/geometry.h"
#include "mesh/solid_probe.h"

namespace rad::meshing {
namespace {

/// Surfaces closer than this times the scene diagonal touch.
constexpr double kContactTolerance = 1e-5;
/// Parts cut away that are smaller than this share of their piece are round-off (slivers
/// between nearly coincident lines) and go unreported.
constexpr double kNegligibleCut = 1e-9;

/// One stretch of a contact line, in 3D; ends that are vertices of the touching piece keep
/// their ids.
struct Contact3 {
  glm::dvec3 a, b;
  int aId = -1, bId = -1;
};

/// Whether an edge whose ends lie at signed distances dp and dq from a plane crosses it, each
/// end farther than `tolerance` from it.
bool crossesPlane(double dp, double dq, double tolerance) {
  return (dp < -tolerance && dq > tolerance) || (dp > tolerance && dq < -tolerance);
}

/// The points of piece s's border in the plane of piece r (within `tolerance`): its corners
/// there (with their ids) and where its edges cross the plane (id -1); and the range [lo, hi]
/// of signed distances of its corners from that plane.
std::vector<std::pair<glm::dvec3, int>> pointsInPlane(const PointTable& table, const Piece& r,
                                                      const Piece& s, double tolerance,
                                                      double& lo, double& hi) {
  std::vector<std::pair<glm::dvec3, int>> on;
  const glm::dvec3& nr = r.frame.normal;
  for (const auto& ring : s.rings)
    for (size_t k = 0; k < ring.size(); ++k) {
      const glm::dvec3 &p = table[ring[k]], &q = table[ring[(k + 1) % ring.size()]];
      const double dp = glm::dot(nr, p - r.frame.origin), dq = glm::dot(nr, q - r.frame.origin);
      lo = std::min(lo, dp);
      hi = std::max(hi, dp);
      if (std::abs(dp) <= tolerance) on.push_back({p, ring[k]});
      if (crossesPlane(dp, dq, tolerance)) on.push_back({p + (q - p) * (dp / (dp - dq)), -1});
    }
  return on;
}

/// Sorts the points along the direction `along`.
void sortAlong(std::vector<std::pair<glm::dvec3, int>>& on, const glm::dvec3& along) {
  std::sort(on.begin(), on.end(), [&](const auto& x, const auto& y) {
    return glm::dot(along, x.first) < glm::dot(along, y.first);
  });
}

/// The stretches between consecutive points (sorted along the line) whose middles lie in s,
/// joined where they meet.
std::vector<Contact3> stretchesIn(const PointTable& table, const Piece& s,
                                  const std::vector<std::pair<glm::dvec3, int>>& on,
                                  double tolerance) {
  std::vector<Contact3> out;
  for (size_t i = 0; i + 1 < on.size(); ++i) {
    const glm::dvec3 &p = on[i].first, &q = on[i + 1].first;
    if (glm::length(q - p) <= tolerance || !insideOrOn(table, s, (p + q) * 0.5, tolerance)) continue;
    if (!out.empty() && glm::length(out.back().b - p) <= tolerance)
      out.back().b = q, out.back().bId = on[i + 1].second;  // joined to the last stretch
    else
      out.push_back({p, q, on[i].second, on[i + 1].second});
  }
  return out;
}

/// Where piece s meets the plane of piece r, if s reaches r's lit side (either side when r is
/// two-sided) and touches or pierces the plane within `tolerance`: the stretches of the line of
/// the two planes that lie in s (one per stretch, so a wall with a doorway standing on a floor
/// gives two).
std::vector<Contact3> contactsOf(const PointTable& table, const Piece& r, bool rTwoSided,
                                 const Piece& s, double tolerance) {
  const glm::dvec3 &nr = r.frame.normal, &ns = s.frame.normal;
  if (std::abs(glm::dot(nr, ns)) > 1 - 1e-9) return {};  // parallel planes
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  auto on = pointsInPlane(table, r, s, tolerance, lo, hi);
  const bool lit = hi > tolerance || (rTwoSided && lo < -tolerance);
  if (!lit || lo > tolerance || hi < -tolerance || on.size() < 2) return {};
  sortAlong(on, glm::normalize(glm::cross(nr, ns)));
  return stretchesIn(table, s, on, tolerance);
}

/// What every step of cutAtContacts shares: the pieces as they were before any cut (contacts
/// come from the uncut pieces), their boxes padded by the tolerance, and the points made.
struct Context {
  Context(const Scene& scene, PointTable& table, const std::vector<Piece>& pieces)
      : scene(scene), table(table), original(pieces),
        tolerance(kContactTolerance * scene.diagonal()),
        box(paddedBoxes(table, pieces, tolerance)), boxes(box), made(tolerance),
        stamp(pieces.size(), -1), coplanar(scene, table, original, tolerance) {}

  const Scene& scene;
  PointTable& table;
  const std::vector<Piece> original;
  const double tolerance;
  const std::vector<Box> box;  ///< per piece
  PieceBoxes boxes;
  SpatialHash made;        ///< points the cuts made, in cells of the tolerance
  std::vector<int> stamp;  ///< the last piece each piece was a candidate for
  std::optional<SolidProbe> probe;  ///< rays against the uncut pieces, made when first asked
  const CoplanarPieces coplanar;  ///< over the uncut pieces

  /// Whether point q of piece r's plane (in its frame), just off its lit side, is inside a solid.
  bool insideSolid(size_t r, const glm::dvec2& q) {
    if (!probe) probe.emplace(scene, table, original);
    const PlaneFrame& frame = original[r].frame;
    return probe->insideSolid(frame.lift(q), frame.normal);
  }
};

/// Whether pieces r and s are faces of one object of a mesh file: its folds meet along its
/// own edges, where a contact line cuts nothing, and a model's parts that pass through each
/// other (a tessellated knob through its rose) are its modeller's business; cutting them
/// multiplied a staircase's brass fittings' elements twentyfold.
bool sameObject(const Context& cx, size_t r, size_t s) {
  const int surface = cx.original[r].surface;
  return surface == cx.original[s].surface && cx.scene.surfaces[size_t(surface)].fromMeshFile;
}

/// The pieces whose boxes meet piece r's, each once, but those of its own object.
std::vector<int> candidates(Context& cx, size_t r) {
  std::vector<int> out;
  cx.boxes.visit(r, [&](int s) {
    if (s == int(r) || cx.stamp[size_t(s)] == int(r)) return;
    cx.stamp[size_t(s)] = int(r);
    if (!sameObject(cx, r, size_t(s)) && boxesMeet(cx.box[r], cx.box[size_t(s)])) out.push_back(s);
  });
  return out;
}

/// Takes point `id` at p as the nearest to x so far if it is no farther than `best`.
void takeIfNearer(const glm::dvec3& p, int id, const glm::dvec3& x, double& best, int& found) {
  if (glm::length(p - x) <= best) best = glm::length(p - x), found = id;
}

/// Takes the corner of piece p nearest to x if it is no farther than `best`.
void nearestCorner(const Context& cx, size_t p, const glm::dvec3& x, double& best, int& found) {
  for (const auto& ring : cx.original[p].rings)
    for (int id : ring) takeIfNearer(cx.table[id], id, x, best, found);
}

/// The id of a new point x: a corner of piece r or s, or a point made earlier, within the
/// tolerance (so that both pieces at a contact share their points); else x, made now.
int snap(Context& cx, const glm::dvec3& x, size_t r, size_t s) {
  int found = -1;
  double best = cx.tolerance;
  for (size_t p : {r, s}) nearestCorner(cx, p, x, best, found);
  const glm::dvec3 pad(cx.tolerance);
  cx.made.visit(x - pad, x + pad, [&](int id) { takeIfNearer(cx.table[id], id, x, best, found); });
  if (found >= 0) return found;
  const int id = cx.table.id(x);
  cx.made.insert(x, id);
  return id;
}

/// Which side of the line the solid side of s (behind it) lies on in r's frame: +1 left, -1
/// right; 0 when light may be on both sides of s or of r.
int solidSide(const Context& cx, size_t r, size_t s, const ContactLine2& line) {
  const Piece &pr = cx.original[r], &ps = cx.original[s];
  if (cx.scene.surfaces[size_t(pr.surface)].twoSided || cx.scene.surfaces[size_t(ps.surface)].twoSided)
    return 0;
  const glm::dvec3 &nr = pr.frame.normal, &ns = ps.frame.normal;
  const glm::dvec3 behind = -(ns - glm::dot(ns, nr) * nr);
  const glm::dvec2 w(glm::dot(behind, pr.frame.u), glm::dot(behind, pr.frame.v));
  const glm::dvec2 d = line.b - line.a;
  return glm::dot(w, glm::dvec2(-d.y, d.x)) > 0 ? 1 : -1;
}

/// The contact c of piece s with piece r as a line in r's frame, its ends snapped.
ContactLine2 contactLine(Context& cx, size_t r, size_t s, const Contact3& c) {
  const PlaneFrame& frame = cx.original[r].frame;
  ContactLine2 line;
  line.aId = c.aId >= 0 ? c.aId : snap(cx, c.a, r, s);
  line.bId = c.bId >= 0 ? c.bId : snap(cx, c.b, r, s);
  line.a = frame.project(cx.table[line.aId]);
  line.b = frame.project(cx.table[line.bId]);
  line.solid = solidSide(cx, r, s, line);
  return line;
}

/// The contact lines on piece r, with the surface each comes from, and the pieces lying on it.
struct Lines {
  std::vector<ContactLine2> lines;
  std::vector<int> from;
  std::vector<int> covering;  ///< pieces lying on r that cover what is under them
};

/// The edges of piece s (lying on r) as cover lines in r's frame.
void addCoverLines(const Context& cx, size_t r, size_t s, Lines& out) {
  const Piece& ps = cx.original[s];
  const PlaneFrame& frame = cx.original[r].frame;
  for (const auto& ring : ps.rings)
    for (size_t k = 0; k < ring.size(); ++k) {
      ContactLine2 line;
      line.aId = ring[k];
      line.bId = ring[(k + 1) % ring.size()];
      line.a = frame.project(cx.table[line.aId]);
      line.b = frame.project(cx.table[line.bId]);
      line.cover = true;
      out.lines.push_back(line);
      out.from.push_back(ps.surface);
    }
  out.covering.push_back(int(s));
}

/// Where other pieces touch or pierce piece r, or lie on it.
Lines contactLinesOf(Context& cx, size_t r) {
  Lines out;
  const bool twoSided = cx.scene.surfaces[size_t(cx.original[r].surface)].twoSided;
  for (int s : candidates(cx, r)) {
    if (cx.coplanar.covers(size_t(s), r)) addCoverLines(cx, r, size_t(s), out);
    for (const Contact3& c : contactsOf(cx.table, cx.original[r], twoSided, cx.original[size_t(s)], cx.tolerance)) {
      // Only lines that come near the piece (a floor's plane crosses every face of a mesh
      // standing on it, far from most of them).
      if (!boxesMeet(cx.box[r], Box{glm::min(c.a, c.b), glm::max(c.a, c.b)})) continue;
      out.lines.push_back(contactLine(cx, r, size_t(s), c));
      out.from.push_back(cx.original[size_t(s)].surface);
    }
  }
  return out;
}

/// Whether the line runs along one of piece r's own edges.
bool alongEdge(const Context& cx, size_t r, const ContactLine2& line) {
  const Piece& piece = cx.original[r];
  for (const auto& ring : piece.rings)
    for (size_t k = 0; k < ring.size(); ++k) {
      const auto [a, b] = projectedEdge(cx.table, piece, ring, k);
      if (segmentDistance(line.a, a, b) <= cx.tolerance &&
          segmentDistance(line.b, a, b) <= cx.tolerance)
        return true;
    }
  return false;
}

/// Whether the line's solid side faces into piece r.
bool solidInwards(const Context& cx, size_t r, const ContactLine2& line) {
  if (line.solid == 0) return false;
  const glm::dvec2 d = line.b - line.a, left(-d.y, d.x);
  const glm::dvec2 probe = (line.a + line.b) * 0.5 + left * (1e-3 * line.solid);
  return insideOrOn(cx.table, cx.original[r], cx.original[r].frame.lift(probe), 0.0);
}

/// Lines along the piece's own edges (a wall standing on a floor's edge, a mesh's folds)
/// cut nothing; unless one has its solid side inwards (the piece may lie under a block),
/// no arrangement is needed.
bool cutsNothing(const Context& cx, size_t r, const std::vector<ContactLine2>& lines) {
  if (std::any_of(lines.begin(), lines.end(), [](const auto& l) { return l.cover; })) return false;
  return std::all_of(lines.begin(), lines.end(), [&](const auto& l) { return alongEdge(cx, r, l); }) &&
         std::none_of(lines.begin(), lines.end(), [&](const auto& l) { return solidInwards(cx, r, l); });
}

/// The id of point q of the cut in piece r's frame: the cut's own id, or a snapped one.
int idOf(Context& cx, size_t r, const glm::dvec2& q, int id) {
  return id >= 0 ? id : snap(cx, cx.original[r].frame.lift(q), r, r);
}

/// Kept ring k of the cut as point ids, repeated points dropped.
std::vector<int> keptRing(Context& cx, size_t r, const ContactCut& cut, size_t k) {
  std::vector<int> ring;
  for (size_t i = 0; i < cut.kept.rings[k].size(); ++i) {
    int id = idOf(cx, r, cut.kept.rings[k][i], cut.kept.ids[k][i]);
    if (ring.empty() || ring.back() != id) ring.push_back(id);
  }
  while (ring.size() > 1 && ring.back() == ring.front()) ring.pop_back();
  return ring;
}

/// Adds the edges of kept ring k that are contact lines to `across`.
void addAcrossEdges(Context& cx, size_t r, const ContactCut& cut, size_t k,
                    std::set<std::pair<int, int>>& across) {
  const size_t m = cut.kept.rings[k].size();
  for (size_t i = 0; i < m; ++i)
    if (cut.contactEdge[k][i]) {
      int p = idOf(cx, r, cut.kept.rings[k][i], cut.kept.ids[k][i]);
      int q = idOf(cx, r, cut.kept.rings[k][(i + 1) % m], cut.kept.ids[k][(i + 1) % m]);
      if (p != q) across.insert(std::minmax(p, q));
    }
}

/// Adds kept ring k of the cut to the piece's rings (unless it collapsed), its contact edges
/// to `across`.
void keepRing(Context& cx, size_t r, const ContactCut& cut, size_t k, Piece& piece,
              std::set<std::pair<int, int>>& across) {
  std::vector<int> ring = keptRing(cx, r, cut, k);
  addAcrossEdges(cx, r, cut, k, across);
  if (ring.size() >= 3) piece.rings.push_back(std::move(ring));
}

/// Adds kept line k of the cut to the piece's lines and to `across`.
void keepLine(Context& cx, size_t r, const ContactCut& cut, size_t k, Piece& piece,
              std::set<std::pair<int, int>>& across) {
  int p = idOf(cx, r, cut.kept.lines[k][0], cut.kept.lineIds[k][0]);
  int q = idOf(cx, r, cut.kept.lines[k][1], cut.kept.lineIds[k][1]);
  if (p == q) return;
  piece.lines.push_back({p, q});
  across.insert(std::minmax(p, q));
}

/// Piece r becomes what the cut kept: its rings, and the contact lines inside as lines
/// (added to `across` too).
void keepCut(Context& cx, size_t r, const ContactCut& cut, Piece& piece,
             std::set<std::pair<int, int>>& across) {
  piece.rings.clear();
  for (size_t k = 0; k < cut.kept.rings.size(); ++k) keepRing(cx, r, cut, k, piece, across);
  for (size_t k = 0; k < cut.kept.lines.size(); ++k) keepLine(cx, r, cut, k, piece, across);
}

/// The signed area of the polygon's rings (counter-clockwise positive).
double ringsArea(const Polygon2& poly) {
  double area = 0;
  for (const auto& ring : poly.rings)
    for (size_t k = 0; k < ring.size(); ++k)
      area += 0.5 * (ring[k].x * ring[(k + 1) % ring.size()].y - ring[(k + 1) % ring.size()].x * ring[k].y);
  return area;
}

/// The surfaces the contact lines `by` come from, sorted, each once.
std::vector<int> surfacesOf(const std::vector<int>& by, const std::vector<int>& from) {
  std::set<int> surfaces;
  for (int k : by) surfaces.insert(from[size_t(k)]);
  return {surfaces.begin(), surfaces.end()};
}

/// Records the parts of a piece of surface `surface` (`poly` before the cut) that the cut
/// left out, slivers apart, each with the surfaces that enclosed it.
void recordCutAway(const ContactCut& cut, const Polygon2& poly, int surface,
                   const std::vector<int>& from, std::vector<CutAway>& cutAway) {
  const double pieceArea = ringsArea(poly);
  for (const auto& removed : cut.removed) {
    if (removed.area <= kNegligibleCut * std::abs(pieceArea)) continue;  // a sliver between lines
    cutAway.push_back({surface, removed.area, surfacesOf(removed.by, from)});
  }
}

/// Drops the pieces with no ring left.
void dropEmpty(std::vector<Piece>& pieces) {
  pieces.erase(std::remove_if(pieces.begin(), pieces.end(),
                              [](const Piece& p) { return p.rings.empty(); }),
               pieces.end());
}

}  // namespace

ContactCuts cutAtContacts(const Scene& scene, PointTable& table, std::vector<Piece>& pieces,
                          StageTimes& stages) {
  auto start = StageTimes::Clock::now();
  Context cx(scene, table, pieces);  // the uncut pieces, indexed by box
  ContactCuts out;
  StageProgress progress("contact lines: pieces", pieces.size());
  for (size_t r = 0; r < pieces.size(); ++r) {
    progress.update(r);
    // Find where other pieces touch or pierce piece r.
    const Lines found = contactLinesOf(cx, r);
    out.lines += int(found.lines.size());
    start = stages.add("contact lines", start);
    // Lines along its own edges only, no solid side facing in: it stays whole.
    if (cutsNothing(cx, r, found.lines)) continue;
    // Cut it along them, leaving out what they enclose.
    const Polygon2 poly = projectedRings(table, pieces[r]);
    const auto covered = [&](const glm::dvec2& q) {
      const glm::dvec3 p = cx.original[r].frame.lift(q);
      return std::any_of(found.covering.begin(), found.covering.end(),
                         [&](int s) { return insideOrOn(cx.table, cx.original[size_t(s)], p, 0.0); });
    };
    const ContactCut cut = cutAlongContacts(poly, found.lines,
                                            [&](const glm::dvec2& q) { return cx.insideSolid(r, q); }, covered,
                                            cx.coplanar.innerEdges(r));
    // Take back what is kept, as point ids, and say what was left out.
    keepCut(cx, r, cut, pieces[r], out.across);
    recordCutAway(cut, poly, pieces[r].surface, found.from, out.cutAway);
    start = stages.add("contact cuts", start);
  }
  // Drop the pieces left out entirely.
  dropEmpty(pieces);
  stages.add("contact cuts", start);
  return out;
}

}  // namespace rad::meshing
