// Planar pieces ▸ elements, with the points on shared boundaries agreed between neighbours.
//
// Every boundary edge is first cut at the corners of other pieces that lie on it and then into
// equal parts; the parts (segments) are keyed by their end points, so two pieces sharing an
// edge compute the very same points on it. Delaunay refinement may still split a boundary
// part (encroachment); such points are added to the shared segment and its other users are
// meshed again until all agree.
#include "mesh/boundary_agreement.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/base/error.h"
#include "mesh/base/progress.h"
#include "mesh/base/spatial_hash.h"
#include "mesh/scene/geometry.h"

namespace rad::meshing {
namespace {

/// Points on a boundary closer than this times the scene diagonal to an edge lie on it.
constexpr double kOnEdgeTolerance = 1e-7;
/// Meshing passes allowed for neighbouring pieces to agree on shared boundary points.
constexpr int kMaxAgreementRounds = 200;

/// A boundary part between two corners, cut at parameters t in (0, 1) from a to b (a < b).
struct Segment {
  int a = -1, b = -1;
  std::vector<double> t;
  std::vector<int> users;  ///< pieces whose boundary runs along it
  bool fine = false;       ///< split finer (a contact line across a surface)
};

/// Adds piece p to the segment's users (pieces come in order, each edge of one after the
/// other).
void addUser(Segment& s, int piece) {
  if (s.users.empty() || s.users.back() != piece) s.users.push_back(piece);
}

/// One edge of a piece's boundary chain: a segment, walked from a to b or back.
struct ChainEdge {
  int segment;
  bool forward;
};

/// A piece's boundary as point ids, ring by ring and then line by line (lines with their last
/// point too), and for each point the chain edge it starts.
struct BoundaryIds {
  std::vector<std::vector<int>> ids, edgeOf;
};

/// The corners' grid has at most this many cells along its longest side.
constexpr double kMaxPointCells = 4096;

/// The ids, sorted and each once.
std::vector<int> sortedUnique(std::vector<int> ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

/// Grows the box [lo, hi] around the points (ids).
void bounds(const PointTable& table, const std::vector<int>& ids, glm::dvec3& lo, glm::dvec3& hi) {
  for (int i : ids) {
    lo = glm::min(lo, table[i]);
    hi = glm::max(hi, table[i]);
  }
}

/// The points (ids) in a hash of about 2 ∛n cells along the widest side of their box, or of
/// cells no larger than `typicalEdge` (at most kMaxPointCells along that side) if those are finer.
SpatialHash pointHash(const PointTable& table, const std::vector<int>& ids, double typicalEdge) {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  bounds(table, ids, lo, hi);
  double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-300});
  int cells = std::clamp(int(2 * std::cbrt(double(ids.size()))), 1, 256);
  // No larger than a typical edge: a finely tessellated model (300 000 triangles a few
  // centimetres across) put thousands of its corners in each cell of the room's grid, and
  // every edge visited them all.
  SpatialHash hash(std::min(extent / cells, std::max(typicalEdge, extent / kMaxPointCells)) * (1 + 1e-9), lo);
  for (int i : ids) hash.insert(table[i], i);
  return hash;
}

/// The index of the boundary edge of `poly` (rings, then lines) nearest to q, as
/// {ring or line, edge}.
std::pair<size_t, size_t> nearestEdge(const Polygon2& poly, const glm::dvec2& q) {
  double best = HUGE_VAL;
  std::pair<size_t, size_t> nearest{0, 0};
  const size_t rings = poly.rings.size();
  for (size_t c = 0; c < rings + poly.lines.size(); ++c) {
    const auto& pts = c < rings ? poly.rings[c] : poly.lines[c - rings];
    const size_t edges = c < rings ? pts.size() : pts.size() - 1;
    for (size_t k = 0; k < edges; ++k) {
      double dist = segmentDistance(q, pts[k], pts[(k + 1) % pts.size()]);
      if (dist < best) best = dist, nearest = {c, k};
    }
  }
  return nearest;
}

/// Meshes a set of pieces at one edge length so that shared boundaries agree.
class PieceMesher {
 public:
  /// Edges in `fine` (point id pairs, lower first) are split into parts maxEdge / fineRatio.
  PieceMesher(const Scene& scene, PointTable& table, const std::vector<Piece>& pieces,
              double maxEdge, double tolerance, const std::set<std::pair<int, int>>& fine,
              double fineRatio)
      : scene_(scene), table_(table), pieces_(pieces), maxEdge_(maxEdge),
        tolerance_(tolerance), fine_(fine), fineRatio_(fineRatio) {}

  /// Triangles as point ids, per piece, and the agreement passes it took; the stages' times
  /// go to `stages`.
  PieceTriangles run(StageTimes& stages) {
    PieceTriangles out;
    auto start = StageTimes::Clock::now();
    cutBoundaries();
    start = stages.add("boundary points", start);
    results_.resize(pieces_.size());
    budget_.assign(pieces_.size(), 0);
    std::vector<bool> dirty(pieces_.size(), true);
    out.rounds = 1;
    bool again = meshDirty(dirty, 1);
    start = stages.add("elements", start);
    while (again) again = meshDirty(dirty, ++out.rounds);
    stages.add("boundary agreement", start);
    out.triangles = std::move(results_);
    out.unresolved = unresolved_;
    for (int p : leftOut_) out.leftOut += out.triangles[size_t(p)].empty();
    return out;
  }

 private:
  /// Meshing round `round`: meshes the pieces marked dirty, marking those whose shared points
  /// changed (unless this is the last round); false when none was dirty or this was the last
  /// round.
  bool meshDirty(std::vector<bool>& dirty, int round) {
    std::vector<int> todo;
    for (size_t p = 0; p < pieces_.size(); ++p)
      if (dirty[p]) todo.push_back(int(p));
    if (todo.empty()) return false;
    std::fill(dirty.begin(), dirty.end(), false);
    const bool last = round == kMaxAgreementRounds;
    StageProgress progress(round == 1 ? "elements: pieces" : "boundary agreement round " + std::to_string(round) + ": pieces",
                           todo.size());
    for (size_t k = 0; k < todo.size(); ++k) {
      progress.update(k);
      meshPiece(todo[k], last ? nullptr : &dirty);
    }
    return !last;
  }

  glm::dvec3 pointOn(const Segment& s, double t) const {
    return table_[s.a] + (table_[s.b] - table_[s.a]) * t;
  }

  /// Every corner of every ring and line, each once.
  std::vector<int> allCorners() const {
    std::vector<int> corners;
    for (const auto& piece : pieces_) {
      for (const auto& ring : piece.rings) corners.insert(corners.end(), ring.begin(), ring.end());
      for (const auto& line : piece.lines) corners.insert(corners.end(), line.begin(), line.end());
    }
    return sortedUnique(std::move(corners));
  }

  /// The median length of the pieces' ring edges.
  double medianEdge() const {
    std::vector<double> lengths;
    for (const auto& piece : pieces_)
      for (const auto& ring : piece.rings)
        for (size_t k = 0; k < ring.size(); ++k) lengths.push_back(glm::length(table_[ring[(k + 1) % ring.size()]] - table_[ring[k]]));
    return median(std::move(lengths));
  }

  /// Cuts every ring edge at the ring corners of other pieces lying on it, then into parts
  /// no longer than maxEdge.
  void cutBoundaries() {
    const SpatialHash grid = pointHash(table_, allCorners(), medianEdge());
    chains_.resize(pieces_.size());
    for (size_t p = 0; p < pieces_.size(); ++p)
      for (const auto& ring : pieces_[p].rings)
        chains_[p].push_back(cutChain(int(p), ring, true, grid));
    // Lines after the rings, as open chains.
    for (size_t p = 0; p < pieces_.size(); ++p)
      for (const auto& line : pieces_[p].lines)
        chains_[p].push_back(cutChain(int(p), {line[0], line[1]}, false, grid));
  }

  /// The chain of segments along the points (ids) of piece p, closed for a ring.
  std::vector<ChainEdge> cutChain(int piece, const std::vector<int>& points, bool closed,
                                  const SpatialHash& grid) {
    std::vector<ChainEdge> chain;
    for (size_t k = 0; k + (closed ? 0 : 1) < points.size(); ++k)
      cutEdge(piece, points[k], points[(k + 1) % points.size()], grid, chain);
    return chain;
  }

  /// The corners lying on the edge from `from` to `to` (within the tolerance), as
  /// (parameter along the edge, id), in order along it.
  std::vector<std::pair<double, int>> cornersOn(int from, int to, const SpatialHash& grid) const {
    glm::dvec3 a = table_[from], b = table_[to], d = b - a;
    double len2 = glm::dot(d, d);
    std::vector<std::pair<double, int>> cuts;
    const glm::dvec3 pad(tolerance_);
    auto take = [&](int c) {
      if (c == from || c == to) return;
      double t = glm::dot(table_[c] - a, d) / len2;
      if (t > 0 && t < 1 && glm::length(a + d * t - table_[c]) <= tolerance_) cuts.emplace_back(t, c);
    };
    // A long edge askew to the grid: its box holds far more cells than lie along it, so it is
    // walked in parts of a cell's length, each part's box visited (a point near two parts is
    // found twice, kept once).
    const double cell = grid.cellSize();
    const glm::dvec3 span = glm::abs(d) + 2.0 * pad;
    const double parts = std::ceil(std::sqrt(len2) / cell);
    if ((span.x / cell + 1) * (span.y / cell + 1) * (span.z / cell + 1) <= 27 * parts) {
      grid.visit(glm::min(a, b) - pad, glm::max(a, b) + pad, take);
    } else {
      for (double k = 0; k < parts; ++k) {
        const glm::dvec3 p = a + d * (k / parts), q = a + d * ((k + 1) / parts);
        grid.visit(glm::min(p, q) - pad, glm::max(p, q) + pad, take);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    return cuts;
  }

  /// Appends the edge from `from` to `to` of piece p to its chain, cut at the corners on it.
  void cutEdge(int piece, int from, int to, const SpatialHash& grid, std::vector<ChainEdge>& chain) {
    std::vector<std::pair<double, int>> cuts = cornersOn(from, to, grid);
    int prev = from;
    cuts.emplace_back(1.0, to);
    const bool fine = fine_.count(std::minmax(from, to)) > 0;
    for (const auto& [t, c] : cuts) {
      if (c == prev) continue;
      chain.push_back({segmentBetween(prev, c, piece, fine), prev < c});
      prev = c;
    }
  }

  /// Cuts s into equal parts no longer than the element edge (finer for a fine segment).
  void splitEvenly(Segment& s) const {
    double part = s.fine ? maxEdge_ / fineRatio_ : maxEdge_;
    int n = std::max(1, int(std::ceil(glm::length(table_[s.b] - table_[s.a]) / part - 1e-9)));
    s.t.clear();
    for (int k = 1; k < n; ++k) s.t.push_back(double(k) / n);
  }

  /// The segment between points p and q (made when new), with `piece` among its users.
  int segmentBetween(int p, int q, int piece, bool fine) {
    auto key = std::minmax(p, q);
    auto [it, added] = segmentIndex_.emplace(key, int(segments_.size()));
    if (added) segments_.push_back(Segment{key.first, key.second, {}, {}, false});
    Segment& s = segments_[it->second];
    if (added || (fine && !s.fine)) {  // equal parts, finer if any user asks
      s.fine = s.fine || fine;
      splitEvenly(s);
    }
    addUser(s, piece);
    return it->second;
  }

  /// Appends the points (ids) of a chain edge to `points`: its first end and the points
  /// inside it, in the direction it is walked.
  void edgePoints(const ChainEdge& edge, std::vector<int>& points) {
    const Segment& s = segments_[edge.segment];
    points.push_back(edge.forward ? s.a : s.b);
    for (size_t j = 0; j < s.t.size(); ++j) {
      double t = edge.forward ? s.t[j] : s.t[s.t.size() - 1 - j];
      points.push_back(table_.id(pointOn(s, t)));
    }
  }

  /// Appends the points (ids) of the chain to `points`, each with the chain edge it starts;
  /// an open chain (a line) ends with its last point.
  void chainPoints(const std::vector<ChainEdge>& chain, bool open, std::vector<int>& points,
                   std::vector<int>& edges) {
    for (size_t k = 0; k < chain.size(); ++k) {
      edgePoints(chain[k], points);
      edges.resize(points.size(), int(k));
    }
    if (open && !chain.empty()) {
      const Segment& s = segments_[chain.back().segment];
      points.push_back(chain.back().forward ? s.b : s.a);
      edges.push_back(int(chain.size()) - 1);
    }
  }

  /// The boundary of piece p as point ids, ring by ring and then line by line.
  BoundaryIds boundary(int p) {
    BoundaryIds out;
    const size_t rings = pieces_[p].rings.size();
    for (size_t c = 0; c < chains_[p].size(); ++c) {
      out.ids.emplace_back();
      out.edgeOf.emplace_back();
      chainPoints(chains_[p][c], c >= rings, out.ids.back(), out.edgeOf.back());
    }
    return out;
  }

  /// The boundary in the piece's 2D frame, rings and lines, with their ids.
  Polygon2 boundaryPolygon(int p, const BoundaryIds& b) const {
    const Piece& piece = pieces_[p];
    const size_t rings = piece.rings.size();
    Polygon2 poly;
    for (size_t c = 0; c < b.ids.size(); ++c) {
      std::vector<glm::dvec2> pts;
      for (int id : b.ids[c]) pts.push_back(piece.frame.project(table_[id]));
      (c < rings ? poly.rings : poly.lines).push_back(std::move(pts));
      (c < rings ? poly.ids : poly.lineIds).push_back(b.ids[c]);
    }
    return poly;
  }

  /// The id of point i of piece p's triangulation: the boundary's, a shared point on a
  /// segment (a new one marks the segment's other users dirty), or a point of its own.
  int pointId(int p, const Polygon2& poly, const BoundaryIds& b, const Triangulation2& tri,
              size_t i, std::vector<bool>* dirty) {
    if (tri.ids[i] >= 0) return tri.ids[i];
    if (tri.onBoundary[i] && dirty) return addBoundaryPoint(p, poly, b.edgeOf, tri.points[i], *dirty);
    if (tri.onBoundary[i]) ++unresolved_;
    return table_.id(pieces_[p].frame.lift(tri.points[i]));
  }

  /// Meshes piece p; points the mesher added on a shared boundary are shared (and their
  /// segment's other users marked dirty) unless `dirty` is null (the last round).
  void meshPiece(int p, std::vector<bool>* dirty) {
    const Piece& piece = pieces_[p];
    const BoundaryIds b = boundary(p);
    const Polygon2 poly = boundaryPolygon(p, b);
    // Its first boundary sets its budget: refinement passing points back and forth with a
    // neighbour (a lamp's disk and the fitting through it) grows both boundaries, never it.
    if (!budget_[size_t(p)]) budget_[size_t(p)] = refinementBudget(poly, maxEdge_);
    const Surface& surface = scene_.surfaces[size_t(piece.surface)];
    // A black surface shows no light and receives none: within one element, its elements need
    // no shape (a lamp's disk, cut by the tessellated holder round it, was refined to
    // thousands of elements). A larger one is refined as any other, to element size.
    const bool black = scene_.materials[size_t(surface.material)].reflectance == glm::dvec3(0.0);
    Triangulation2 tri;
    try {
      tri = black && withinElement(poly, maxEdge_) ? meshPolygonAsIs(poly, maxEdge_, surface.where)
                                                   : meshPolygon(poly, maxEdge_, surface.where, piece.meshFace, budget_[size_t(p)]);
    } catch (const InputError&) {
      // A mesh file's face whose outline, cut at contacts and snapped to its neighbours'
      // points, crosses itself (a tiny face of a finely tessellated model) is left out, said
      // in a warning; a scene polygon that does so is the user's to mend.
      if (!piece.meshFace) throw;
      leftOut_.insert(p);
      results_[p].clear();
      return;
    }
    std::vector<int> global(tri.points.size());
    for (size_t i = 0; i < tri.points.size(); ++i) global[i] = pointId(p, poly, b, tri, i, dirty);
    auto& out = results_[p];
    out.clear();
    for (const auto& t : tri.triangles) out.push_back({global[t[0]], global[t[1]], global[t[2]]});
  }

  /// The point of segment s (its ends included) within the tolerance of the point at t, or -1.
  int pointNear(const Segment& s, double t) const {
    const double reach = tolerance_ / glm::length(table_[s.b] - table_[s.a]);
    if (t <= reach) return s.a;
    if (t >= 1 - reach) return s.b;
    const auto at = std::lower_bound(s.t.begin(), s.t.end(), t);
    if (at != s.t.end() && *at - t <= reach) return table_.id(pointOn(s, *at));
    if (at != s.t.begin() && t - *std::prev(at) <= reach) return table_.id(pointOn(s, *std::prev(at)));
    return -1;
  }

  /// Registers a point the mesher put on piece p's boundary or on one of its lines with the
  /// shared segment, and marks the segment's other users for meshing again; a point within the
  /// tolerance of one the segment has is that one. (Refinement grading into a sliver's corner
  /// halves a segment down to points one rounding step apart, which CGAL's mesher, given them
  /// back, splits without end.)
  int addBoundaryPoint(int p, const Polygon2& poly, const std::vector<std::vector<int>>& edgeOf,
                       const glm::dvec2& q, std::vector<bool>& dirty) {
    const auto [c, k] = nearestEdge(poly, q);
    ChainEdge edge = chains_[p][c][size_t(edgeOf[c][k])];
    Segment& s = segments_[edge.segment];
    glm::dvec3 x = pieces_[p].frame.lift(q), d = table_[s.b] - table_[s.a];
    double t = std::clamp(glm::dot(x - table_[s.a], d) / glm::dot(d, d), 1e-12, 1 - 1e-12);
    if (const int near = pointNear(s, t); near >= 0) return near;
    s.t.insert(std::upper_bound(s.t.begin(), s.t.end(), t), t);
    for (int user : s.users)
      if (user != p) dirty[user] = true;
    return table_.id(pointOn(s, t));
  }

  const Scene& scene_;
  PointTable& table_;
  const std::vector<Piece>& pieces_;
  double maxEdge_, tolerance_;
  const std::set<std::pair<int, int>>& fine_;
  double fineRatio_;
  std::vector<Segment> segments_;
  std::map<std::pair<int, int>, int> segmentIndex_;
  std::vector<std::vector<std::vector<ChainEdge>>> chains_;
  std::vector<std::vector<std::array<int, 3>>> results_;
  std::vector<size_t> budget_;  ///< per piece: the vertices its refinement may make
  int unresolved_ = 0;
  std::set<int> leftOut_;  ///< mesh file faces that could not be meshed
};

}  // namespace

PieceTriangles meshPieces(const Scene& scene, const MeshSettings& settings, PointTable& table,
                          const std::vector<Piece>& pieces,
                          const std::set<std::pair<int, int>>& fine, StageTimes& stages) {
  PieceMesher mesher(scene, table, pieces, settings.maxElementEdge,
                     kOnEdgeTolerance * scene.diagonal(), fine, settings.contactGrading);
  return mesher.run(stages);
}

}  // namespace rad::meshing
