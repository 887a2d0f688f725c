// Surfaces ▸ planar pieces ▸ elements ▸ patches.
//
// Planar pieces are meshed into elements (triangles no longer than maxElementEdge) by
// Delaunay refinement. Every boundary edge is first cut at the corners of other pieces that
// lie on it and then into equal parts; the parts are keyed by their end points, so two
// pieces sharing an edge compute the very same points on it. Refinement may still split a
// boundary part (encroachment); such points are added to the shared part and its other users
// are meshed again until all agree. The elements of each piece are then grown into compact
// patches no wider than maxPatchEdge.
#include "mesh/patch_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <set>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "mesh/contact_cutter.h"
#include "mesh/error.h"
#include "mesh/geometry.h"
#include "mesh/polygon_mesher.h"

namespace rad {
namespace {

/// Points on a boundary closer than this times the scene diagonal to an edge lie on it.
constexpr double kOnEdgeTolerance = 1e-7;
/// Surfaces closer than this times the scene diagonal touch.
constexpr double kContactTolerance = 1e-5;
/// Parts cut away that are smaller than this share of their piece are round-off (slivers
/// between nearly coincident lines) and go unreported.
constexpr double kNegligibleCut = 1e-9;
/// Meshing passes allowed for neighbouring pieces to agree on shared boundary points.
constexpr int kMaxAgreementRounds = 200;

/// Every distinct position gets one id, so equal points compare by id.
class PointTable {
 public:
  int id(const glm::dvec3& p) {
    Key k{p.x + 0.0, p.y + 0.0, p.z + 0.0};  // + 0.0 folds -0 into 0
    auto [it, added] = index_.emplace(k, int(points_.size()));
    if (added) points_.push_back(p);
    return it->second;
  }
  const glm::dvec3& operator[](int i) const { return points_[i]; }
  int size() const { return int(points_.size()); }

 private:
  using Key = std::array<double, 3>;
  struct Hash {
    size_t operator()(const Key& k) const {
      std::hash<double> h;
      return h(k[0]) * 73856093u ^ h(k[1]) * 19349663u ^ h(k[2]) * 83492791u;
    }
  };
  std::vector<glm::dvec3> points_;
  std::unordered_map<Key, int, Hash> index_;
};

/// A planar polygon with holes whose ring points are ids in a PointTable, and the contact
/// lines inside it that meshing keeps as element edges.
struct Piece {
  int surface = -1;
  PlaneFrame frame;
  std::vector<std::vector<int>> rings;
  std::vector<std::array<int, 2>> lines;
  bool meshFace = false;  ///< a face of a mesh file
};

/// A uniform grid over point ids, to find the points near a segment.
class PointGrid {
 public:
  PointGrid(const PointTable& table, const std::vector<int>& ids) {
    glm::dvec3 hi(-HUGE_VAL);
    lo_ = glm::dvec3(HUGE_VAL);
    for (int i : ids) {
      lo_ = glm::min(lo_, table[i]);
      hi = glm::max(hi, table[i]);
    }
    double extent = std::max({hi.x - lo_.x, hi.y - lo_.y, hi.z - lo_.z, 1e-300});
    int cells = std::clamp(int(2 * std::cbrt(double(ids.size()))), 1, 256);
    cell_ = extent / cells * (1 + 1e-9);
    for (int i : ids) cells_[cellOf(table[i])].push_back(i);
  }

  /// Calls f(id) for every point in the cells touching the box [lo, hi].
  template <class F>
  void visit(const glm::dvec3& lo, const glm::dvec3& hi, F f) const {
    auto a = cellOf(lo), b = cellOf(hi);
    for (int64_t x = a[0]; x <= b[0]; ++x)
      for (int64_t y = a[1]; y <= b[1]; ++y)
        for (int64_t z = a[2]; z <= b[2]; ++z) {
          auto it = cells_.find({x, y, z});
          if (it != cells_.end())
            for (int i : it->second) f(i);
        }
  }

 private:
  using Cell = std::array<int64_t, 3>;
  struct Hash {
    size_t operator()(const Cell& c) const {
      return size_t(c[0] * 73856093 ^ c[1] * 19349663 ^ c[2] * 83492791);
    }
  };
  Cell cellOf(const glm::dvec3& p) const {
    glm::dvec3 q = (p - lo_) / cell_;
    return {int64_t(std::floor(q.x)), int64_t(std::floor(q.y)), int64_t(std::floor(q.z))};
  }
  glm::dvec3 lo_;
  double cell_ = 1;
  std::unordered_map<Cell, std::vector<int>, Hash> cells_;
};

/// A boundary part between two corners, cut at parameters t in (0, 1) from a to b (a < b).
struct Segment {
  int a = -1, b = -1;
  std::vector<double> t;
  std::vector<int> users;  ///< pieces whose boundary runs along it
  bool fine = false;       ///< split finer (a contact line across a surface)
};

/// Meshes a set of pieces at one edge length so that shared boundaries agree.
class PieceMesher {
 public:
  /// Edges in `fine` (point id pairs, lower first) are split into parts maxEdge / fineRatio.
  PieceMesher(PointTable& table, std::vector<Piece> pieces, double maxEdge, double tolerance,
              std::vector<std::string> wheres, std::set<std::pair<int, int>> fine = {},
              double fineRatio = 1)
      : table_(table), pieces_(std::move(pieces)), wheres_(std::move(wheres)),
        maxEdge_(maxEdge), tolerance_(tolerance), fine_(std::move(fine)), fineRatio_(fineRatio) {}

  /// Triangles as point ids, per piece; rounds counts the agreement passes.
  std::vector<std::vector<std::array<int, 3>>> run(int& rounds) {
    cutBoundaries();
    results_.resize(pieces_.size());
    std::vector<bool> dirty(pieces_.size(), true);
    for (rounds = 1;; ++rounds) {
      std::vector<int> todo;
      for (size_t p = 0; p < pieces_.size(); ++p)
        if (dirty[p]) todo.push_back(int(p));
      if (todo.empty()) break;
      std::fill(dirty.begin(), dirty.end(), false);
      bool last = rounds == kMaxAgreementRounds;
      for (int p : todo) meshPiece(p, last ? nullptr : &dirty);
      if (last) break;
    }
    return std::move(results_);
  }

  const std::vector<Piece>& pieces() const { return pieces_; }
  int unresolvedPoints() const { return unresolved_; }

 private:
  struct ChainEdge {
    int segment;
    bool forward;
  };

  glm::dvec3 pointOn(const Segment& s, double t) const {
    return table_[s.a] + (table_[s.b] - table_[s.a]) * t;
  }

  /// Cuts every ring edge at the ring corners of other pieces lying on it, then into parts
  /// no longer than maxEdge.
  void cutBoundaries() {
    std::vector<int> corners;
    for (const auto& piece : pieces_) {
      for (const auto& ring : piece.rings) corners.insert(corners.end(), ring.begin(), ring.end());
      for (const auto& line : piece.lines) corners.insert(corners.end(), line.begin(), line.end());
    }
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    PointGrid grid(table_, corners);
    chains_.resize(pieces_.size());
    for (size_t p = 0; p < pieces_.size(); ++p)
      for (const auto& ring : pieces_[p].rings) {
        std::vector<ChainEdge> chain;
        for (size_t k = 0; k < ring.size(); ++k)
          cutEdge(int(p), ring[k], ring[(k + 1) % ring.size()], grid, chain);
        chains_[p].push_back(std::move(chain));
      }
    // Lines after the rings, as open chains.
    for (size_t p = 0; p < pieces_.size(); ++p)
      for (const auto& line : pieces_[p].lines) {
        std::vector<ChainEdge> chain;
        cutEdge(int(p), line[0], line[1], grid, chain);
        chains_[p].push_back(std::move(chain));
      }
  }

  void cutEdge(int piece, int from, int to, const PointGrid& grid, std::vector<ChainEdge>& chain) {
    glm::dvec3 a = table_[from], b = table_[to], d = b - a;
    double len2 = glm::dot(d, d);
    std::vector<std::pair<double, int>> cuts;
    glm::dvec3 pad(tolerance_);
    grid.visit(glm::min(a, b) - pad, glm::max(a, b) + pad, [&](int c) {
      if (c == from || c == to) return;
      double t = glm::dot(table_[c] - a, d) / len2;
      if (t <= 0 || t >= 1) return;
      if (glm::length(a + d * t - table_[c]) <= tolerance_) cuts.emplace_back(t, c);
    });
    std::sort(cuts.begin(), cuts.end());
    int prev = from;
    cuts.emplace_back(1.0, to);
    const bool fine = fine_.count(std::minmax(from, to)) > 0;
    for (const auto& [t, c] : cuts) {
      if (c == prev) continue;
      chain.push_back({segmentBetween(prev, c, piece, fine), prev < c});
      prev = c;
    }
  }

  int segmentBetween(int p, int q, int piece, bool fine) {
    auto key = std::minmax(p, q);
    auto [it, added] = segmentIndex_.emplace(key, int(segments_.size()));
    if (added) {
      Segment s;
      s.a = key.first;
      s.b = key.second;
      segments_.push_back(std::move(s));
    }
    Segment& s = segments_[it->second];
    if (added || (fine && !s.fine)) {  // equal parts, finer if any user asks
      s.fine = s.fine || fine;
      double part = s.fine ? maxEdge_ / fineRatio_ : maxEdge_;
      int n = std::max(1, int(std::ceil(glm::length(table_[s.b] - table_[s.a]) / part - 1e-9)));
      s.t.clear();
      for (int k = 1; k < n; ++k) s.t.push_back(double(k) / n);
    }
    auto& users = segments_[it->second].users;
    if (users.empty() || users.back() != piece) users.push_back(piece);
    return it->second;
  }

  /// The boundary of piece p as point ids, ring by ring and then line by line (lines with
  /// their last point too), and for each point the chain edge it starts.
  void boundary(int p, std::vector<std::vector<int>>& ids,
                std::vector<std::vector<int>>& edgeOf) {
    const size_t rings = pieces_[p].rings.size();
    for (size_t c = 0; c < chains_[p].size(); ++c) {
      const auto& chain = chains_[p][c];
      std::vector<int> points, edges;
      for (size_t k = 0; k < chain.size(); ++k) {
        const Segment& s = segments_[chain[k].segment];
        points.push_back(chain[k].forward ? s.a : s.b);
        edges.push_back(int(k));
        for (size_t j = 0; j < s.t.size(); ++j) {
          double t = chain[k].forward ? s.t[j] : s.t[s.t.size() - 1 - j];
          points.push_back(table_.id(pointOn(s, t)));
          edges.push_back(int(k));
        }
      }
      if (c >= rings && !chain.empty()) {  // an open line ends at its last point
        const Segment& s = segments_[chain.back().segment];
        points.push_back(chain.back().forward ? s.b : s.a);
        edges.push_back(int(chain.size()) - 1);
      }
      ids.push_back(std::move(points));
      edgeOf.push_back(std::move(edges));
    }
  }

  void meshPiece(int p, std::vector<bool>* dirty) {
    const Piece& piece = pieces_[p];
    std::vector<std::vector<int>> ids, edgeOf;
    boundary(p, ids, edgeOf);
    const size_t rings = piece.rings.size();
    Polygon2 poly;
    for (size_t c = 0; c < ids.size(); ++c) {
      std::vector<glm::dvec2> pts;
      for (int id : ids[c]) pts.push_back(piece.frame.project(table_[id]));
      (c < rings ? poly.rings : poly.lines).push_back(std::move(pts));
      (c < rings ? poly.ids : poly.lineIds).push_back(ids[c]);
    }
    Triangulation2 tri = meshPolygon(poly, maxEdge_, wheres_[p], piece.meshFace);
    std::vector<int> global(tri.points.size());
    for (size_t i = 0; i < tri.points.size(); ++i) {
      if (tri.ids[i] >= 0)
        global[i] = tri.ids[i];
      else if (tri.onBoundary[i] && dirty)
        global[i] = addBoundaryPoint(p, poly, edgeOf, tri.points[i], *dirty);
      else {
        if (tri.onBoundary[i]) ++unresolved_;
        global[i] = table_.id(piece.frame.lift(tri.points[i]));
      }
    }
    auto& out = results_[p];
    out.clear();
    for (const auto& t : tri.triangles) out.push_back({global[t[0]], global[t[1]], global[t[2]]});
  }

  /// Registers a point the mesher put on piece p's boundary or on one of its lines with the
  /// shared segment, and marks the segment's other users for meshing again.
  int addBoundaryPoint(int p, const Polygon2& poly, const std::vector<std::vector<int>>& edgeOf,
                       const glm::dvec2& q, std::vector<bool>& dirty) {
    double best = HUGE_VAL;
    size_t bestChain = 0, bestK = 0;
    const size_t rings = poly.rings.size();
    for (size_t c = 0; c < rings + poly.lines.size(); ++c) {
      const auto& pts = c < rings ? poly.rings[c] : poly.lines[c - rings];
      const size_t edges = c < rings ? pts.size() : pts.size() - 1;
      for (size_t k = 0; k < edges; ++k) {
        glm::dvec2 a = pts[k], b = pts[(k + 1) % pts.size()];
        glm::dvec2 d = b - a;
        double t = std::clamp(glm::dot(q - a, d) / glm::dot(d, d), 0.0, 1.0);
        double dist = glm::length(a + d * t - q);
        if (dist < best) best = dist, bestChain = c, bestK = k;
      }
    }
    ChainEdge edge = chains_[p][bestChain][size_t(edgeOf[bestChain][bestK])];
    Segment& s = segments_[edge.segment];
    glm::dvec3 x = pieces_[p].frame.lift(q), d = table_[s.b] - table_[s.a];
    double t = std::clamp(glm::dot(x - table_[s.a], d) / glm::dot(d, d), 1e-12, 1 - 1e-12);
    s.t.insert(std::upper_bound(s.t.begin(), s.t.end(), t), t);
    for (int user : s.users)
      if (user != p) dirty[user] = true;
    return table_.id(pointOn(s, t));
  }

  PointTable& table_;
  std::vector<Piece> pieces_;
  std::vector<std::string> wheres_;
  double maxEdge_, tolerance_;
  std::set<std::pair<int, int>> fine_;
  double fineRatio_;
  std::vector<Segment> segments_;
  std::map<std::pair<int, int>, int> segmentIndex_;
  std::vector<std::vector<std::vector<ChainEdge>>> chains_;
  std::vector<std::vector<std::array<int, 3>>> results_;
  int unresolved_ = 0;
};

std::string formatLength(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

/// Splits every polygon into planar pieces; a non-planar one is triangulated, with a warning.
std::vector<Piece> planarPieces(const Scene& scene, PointTable& table,
                                std::vector<std::string>& wheres,
                                std::vector<std::string>& warnings) {
  std::vector<Piece> pieces;
  for (size_t s = 0; s < scene.surfaces.size(); ++s) {
    const Surface& surface = scene.surfaces[s];
    int triangulated = 0;
    double worst = 0;
    for (const auto& polygon : surface.polygons) {
      Piece piece;
      piece.surface = int(s);
      piece.meshFace = surface.fromMeshFile;
      piece.frame = planeFrame(polygon.outer);
      std::vector<Ring> rings{polygon.outer};
      rings.insert(rings.end(), polygon.holes.begin(), polygon.holes.end());
      double off = 0;
      for (const auto& ring : rings) off = std::max(off, maxPlaneDistance(piece.frame, ring));
      for (const auto& ring : rings) {
        std::vector<int> ids;
        for (const auto& q : ring) {
          int id = table.id(q);
          if (ids.empty() || ids.back() != id) ids.push_back(id);  // drop repeated points
        }
        while (ids.size() > 1 && ids.back() == ids.front()) ids.pop_back();
        piece.rings.push_back(std::move(ids));
      }
      if (off <= kPlanarity * ringDiameter(polygon.outer)) {
        pieces.push_back(std::move(piece));
        wheres.push_back(surface.where);
        continue;
      }
      // Not planar: cut into triangles, each planar, sharing their diagonals.
      Polygon2 poly;
      poly.ids = piece.rings;
      for (const auto& ring : piece.rings) {
        std::vector<glm::dvec2> pts;
        for (int id : ring) pts.push_back(piece.frame.project(table[id]));
        poly.rings.push_back(std::move(pts));
      }
      Triangulation2 tri = triangulatePolygon(poly, surface.where);
      for (const auto& t : tri.triangles) {
        Piece part;
        part.surface = int(s);
        part.rings = {{tri.ids[t[0]], tri.ids[t[1]], tri.ids[t[2]]}};
        part.frame = planeFrame({table[part.rings[0][0]], table[part.rings[0][1]],
                                 table[part.rings[0][2]]});
        pieces.push_back(std::move(part));
        wheres.push_back(surface.where);
      }
      ++triangulated;
      worst = std::max(worst, off);
    }
    if (triangulated)
      warnings.push_back(surface.where + " (" + surface.name + "): " +
                         std::to_string(triangulated) +
                         " non-planar polygon(s) triangulated into planar triangles (a vertex lies " +
                         formatLength(worst) + " off the best-fit plane)");
  }
  return pieces;
}

/// The corners of the convex hull of the points (ids), which all lie in `frame`'s plane:
/// Andrew's monotone chain on their projections.
std::vector<int> convexHull(const PointTable& table, const PlaneFrame& frame, std::vector<int> ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (ids.size() < 3) return ids;
  std::vector<std::pair<glm::dvec2, int>> pts;
  for (int id : ids) pts.push_back({frame.project(table[id]), id});
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
    return std::make_pair(a.first.x, a.first.y) < std::make_pair(b.first.x, b.first.y);
  });
  auto turn = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<std::pair<glm::dvec2, int>> hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {  // lower chain
    while (k >= 2 && turn(hull[k - 2].first, hull[k - 1].first, pts[i].first) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && turn(hull[k - 2].first, hull[k - 1].first, pts[i].first) <= 0) --k;
    hull[k++] = pts[i];
  }
  std::vector<int> out;
  for (size_t i = 0; i + 1 < k; ++i) out.push_back(hull[i].second);
  return out;
}

/// The largest distance between two of the points (ids): between two hull corners.
double diameter(const PointTable& table, const std::vector<int>& hull) {
  double widest = 0;
  for (size_t i = 0; i < hull.size(); ++i)
    for (size_t j = i + 1; j < hull.size(); ++j)
      widest = std::max(widest, glm::length(table[hull[i]] - table[hull[j]]));
  return widest;
}

/// Groups the triangles of one planar piece into patches no wider than maxDiameter: each patch
/// grows from the first free triangle in sweep order (along the frame's u axis, then v) to the
/// free edge-neighbours nearest its seed while its diameter allows, so patches are connected
/// and compact. Returns triangle indices per patch.
std::vector<std::vector<int>> growPatches(const PointTable& table, const PlaneFrame& frame,
                                          const std::vector<std::array<int, 3>>& triangles,
                                          double maxDiameter) {
  const int n = int(triangles.size());
  std::vector<glm::dvec2> centre(n);
  std::map<std::pair<int, int>, std::vector<int>> byEdge;
  for (int k = 0; k < n; ++k) {
    const auto& t = triangles[k];
    centre[k] = frame.project((table[t[0]] + table[t[1]] + table[t[2]]) / 3.0);
    for (int i = 0; i < 3; ++i) byEdge[std::minmax(t[i], t[(i + 1) % 3])].push_back(k);
  }
  std::vector<std::vector<int>> neighbours(n);
  for (const auto& [edge, users] : byEdge)
    for (int a : users)
      for (int b : users)
        if (a != b) neighbours[a].push_back(b);
  std::vector<int> order(n);
  for (int k = 0; k < n; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::make_pair(centre[a].x, centre[a].y) < std::make_pair(centre[b].x, centre[b].y);
  });

  std::vector<std::vector<int>> patches;
  std::vector<bool> taken(n, false);
  for (int seed : order) {
    if (taken[seed]) continue;
    std::vector<int> patch, hull;  // the patch's triangles and the corners of its convex hull
    using Candidate = std::pair<double, int>;  // distance to the seed, triangle
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> frontier;
    std::set<int> queued{seed};
    frontier.push({0.0, seed});
    while (!frontier.empty()) {
      int k = frontier.top().second;
      frontier.pop();
      // The patch stays no wider than maxDiameter iff the new corners are within it of each
      // other and of every point of the patch, that is of every hull corner. (The seed always
      // fits: a patch is at least one element, however wide.)
      bool fits = true;
      for (int v : triangles[k]) {
        for (int q : hull) fits = fits && glm::length(table[v] - table[q]) <= maxDiameter;
        if (!hull.empty())
          for (int w : triangles[k]) fits = fits && glm::length(table[v] - table[w]) <= maxDiameter;
      }
      if (!fits) continue;
      taken[k] = true;
      patch.push_back(k);
      hull.insert(hull.end(), triangles[k].begin(), triangles[k].end());
      hull = convexHull(table, frame, std::move(hull));
      for (int m : neighbours[k])
        if (!taken[m] && queued.insert(m).second)
          frontier.push({glm::length(centre[m] - centre[seed]), m});
    }
    patches.push_back(std::move(patch));
  }
  return patches;
}

/// One stretch of a contact line, in 3D; ends that are vertices of the touching piece keep
/// their ids.
struct Contact3 {
  glm::dvec3 a, b;
  int aId = -1, bId = -1;
};

/// True when q, a point of s's plane, lies inside piece s or within `tolerance` of its border.
bool insideOrOn(const PointTable& table, const Piece& s, const glm::dvec3& q, double tolerance) {
  const glm::dvec2 x = s.frame.project(q);
  bool inside = false;
  for (const auto& ring : s.rings)
    for (size_t k = 0; k < ring.size(); ++k) {
      const glm::dvec2 a = s.frame.project(table[ring[k]]);
      const glm::dvec2 b = s.frame.project(table[ring[(k + 1) % ring.size()]]);
      const glm::dvec2 d = b - a;
      const double t = std::clamp(glm::dot(x - a, d) / glm::dot(d, d), 0.0, 1.0);
      if (glm::length(a + d * t - x) <= tolerance) return true;
      if ((a.y > x.y) != (b.y > x.y) && x.x < a.x + (x.y - a.y) * d.x / d.y) inside = !inside;
    }
  return inside;
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
  std::vector<std::pair<glm::dvec3, int>> on;  // points of s's border in r's plane
  for (const auto& ring : s.rings) {
    for (size_t k = 0; k < ring.size(); ++k) {
      const glm::dvec3 &p = table[ring[k]], &q = table[ring[(k + 1) % ring.size()]];
      const double dp = glm::dot(nr, p - r.frame.origin), dq = glm::dot(nr, q - r.frame.origin);
      lo = std::min(lo, dp);
      hi = std::max(hi, dp);
      if (std::abs(dp) <= tolerance) on.push_back({p, ring[k]});
      if ((dp < -tolerance && dq > tolerance) || (dp > tolerance && dq < -tolerance))
        on.push_back({p + (q - p) * (dp / (dp - dq)), -1});
    }
  }
  const bool lit = hi > tolerance || (rTwoSided && lo < -tolerance);
  if (!lit || lo > tolerance || hi < -tolerance || on.size() < 2) return {};
  const glm::dvec3 along = glm::normalize(glm::cross(nr, ns));
  std::sort(on.begin(), on.end(), [&](const auto& x, const auto& y) {
    return glm::dot(along, x.first) < glm::dot(along, y.first);
  });
  // Stretches between consecutive points whose middles lie in s, joined where they meet.
  std::vector<Contact3> out;
  for (size_t i = 0; i + 1 < on.size(); ++i) {
    const glm::dvec3 &p = on[i].first, &q = on[i + 1].first;
    if (glm::length(q - p) <= tolerance || !insideOrOn(table, s, (p + q) * 0.5, tolerance)) continue;
    if (!out.empty() && glm::length(out.back().b - p) <= tolerance) {
      out.back().b = q;
      out.back().bId = on[i + 1].second;
    } else {
      out.push_back({p, q, on[i].second, on[i + 1].second});
    }
  }
  return out;
}

/// Cuts every piece along the lines where other pieces touch or pierce it (a block standing
/// on a floor, a wall meeting a floor, a box pushed into a wall) and leaves out what they
/// enclose (cutAlongContacts). New points within `tolerance` of an existing one are merged
/// with it, so that both pieces at a contact share their points. Records what was left out,
/// and in `across` the edges (point ids) of contact lines that run across a piece.
void cutAtContacts(const Scene& scene, PointTable& table, std::vector<Piece>& pieces,
                   std::vector<std::string>& wheres, double tolerance,
                   std::set<std::pair<int, int>>& across, PatchMesh& out) {
  const size_t n = pieces.size();
  const std::vector<Piece> original = pieces;  // contacts come from the uncut pieces
  // Pieces by bounding box, in a grid over the scene, to find the ones that may touch.
  std::vector<glm::dvec3> lo(n, glm::dvec3(HUGE_VAL)), hi(n, glm::dvec3(-HUGE_VAL));
  glm::dvec3 sceneLo(HUGE_VAL), sceneHi(-HUGE_VAL);
  for (size_t p = 0; p < n; ++p)
    for (const auto& ring : pieces[p].rings)
      for (int id : ring) {
        lo[p] = glm::min(lo[p], table[id] - tolerance);
        hi[p] = glm::max(hi[p], table[id] + tolerance);
      }
  for (size_t p = 0; p < n; ++p) sceneLo = glm::min(sceneLo, lo[p]), sceneHi = glm::max(sceneHi, hi[p]);
  const int cells = std::clamp(int(2 * std::cbrt(double(n))), 1, 64);
  const glm::dvec3 cell = glm::max((sceneHi - sceneLo) / double(cells), glm::dvec3(1e-300));
  auto cellRange = [&](size_t p, glm::ivec3& a, glm::ivec3& b) {
    a = glm::clamp(glm::ivec3(glm::floor((lo[p] - sceneLo) / cell)), 0, cells - 1);
    b = glm::clamp(glm::ivec3(glm::floor((hi[p] - sceneLo) / cell)), 0, cells - 1);
  };
  std::vector<std::vector<int>> grid(size_t(cells) * cells * cells);
  auto at = [&](int x, int y, int z) -> std::vector<int>& { return grid[(size_t(x) * cells + y) * cells + z]; };
  for (size_t p = 0; p < n; ++p) {
    glm::ivec3 a, b;
    cellRange(p, a, b);
    for (int x = a.x; x <= b.x; ++x)
      for (int y = a.y; y <= b.y; ++y)
        for (int z = a.z; z <= b.z; ++z) at(x, y, z).push_back(int(p));
  }
  // New points merge with a corner of the two pieces involved, or with a point made earlier,
  // within the tolerance (so that both pieces at a contact share their points).
  std::unordered_map<uint64_t, std::vector<int>> made;  // by cell of size `tolerance`
  auto cellKey = [&](const glm::dvec3& x, int dx, int dy, int dz) {
    return uint64_t(int64_t(std::floor(x.x / tolerance)) + dx) * 73856093u ^
           uint64_t(int64_t(std::floor(x.y / tolerance)) + dy) * 19349663u ^
           uint64_t(int64_t(std::floor(x.z / tolerance)) + dz) * 83492791u;
  };
  auto snap = [&](const glm::dvec3& x, int r, int s) {
    int found = -1;
    double best = tolerance;
    for (int p : {r, s})
      for (const auto& ring : original[size_t(p)].rings)
        for (int id : ring)
          if (glm::length(table[id] - x) <= best) best = glm::length(table[id] - x), found = id;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = made.find(cellKey(x, dx, dy, dz));
          if (it == made.end()) continue;
          for (int id : it->second)
            if (glm::length(table[id] - x) <= best) best = glm::length(table[id] - x), found = id;
        }
    if (found >= 0) return found;
    const int id = table.id(x);
    made[cellKey(x, 0, 0, 0)].push_back(id);
    return id;
  };

  // The pieces whose boxes meet piece r's, each once.
  std::vector<int> stamp(n, -1);
  auto candidates = [&](size_t r) {
    std::vector<int> out;
    glm::ivec3 a, b;
    cellRange(r, a, b);
    for (int x = a.x; x <= b.x; ++x)
      for (int y = a.y; y <= b.y; ++y)
        for (int z = a.z; z <= b.z; ++z)
          for (int s : at(x, y, z)) {
            if (s == int(r) || stamp[size_t(s)] == int(r)) continue;
            stamp[size_t(s)] = int(r);
            if (!glm::any(glm::lessThan(hi[size_t(s)], lo[r])) &&
                !glm::any(glm::lessThan(hi[r], lo[size_t(s)])))
              out.push_back(s);
          }
    return out;
  };
  std::vector<bool> gone(n, false);
  for (size_t r = 0; r < n; ++r) {
    Piece& piece = pieces[r];
    const bool twoSided = scene.surfaces[piece.surface].twoSided;
    std::vector<ContactLine2> lines;
    std::vector<int> from;  // the surface each line comes from
    for (int s : candidates(r)) {
      for (const Contact3& c : contactsOf(table, original[r], twoSided, original[s], tolerance)) {
        // Only lines that come near the piece (a floor's plane crosses every face of a mesh
        // standing on it, far from most of them).
        if (glm::any(glm::lessThan(glm::max(c.a, c.b), lo[r])) ||
            glm::any(glm::lessThan(hi[r], glm::min(c.a, c.b))))
          continue;
        ContactLine2 line;
        line.aId = c.aId >= 0 ? c.aId : snap(c.a, int(r), s);
        line.bId = c.bId >= 0 ? c.bId : snap(c.b, int(r), s);
        line.a = piece.frame.project(table[line.aId]);
        line.b = piece.frame.project(table[line.bId]);
        // The solid side: behind s, unless light may be on both sides of s or of r.
        if (!twoSided && !scene.surfaces[original[s].surface].twoSided) {
          const glm::dvec3 &nr = piece.frame.normal, &ns = original[s].frame.normal;
          const glm::dvec3 behind = -(ns - glm::dot(ns, nr) * nr);
          const glm::dvec2 w(glm::dot(behind, piece.frame.u), glm::dot(behind, piece.frame.v));
          const glm::dvec2 d = line.b - line.a;
          line.solid = glm::dot(w, glm::dvec2(-d.y, d.x)) > 0 ? 1 : -1;
        }
        lines.push_back(line);
        from.push_back(original[s].surface);
      }
    }
    // Lines along the piece's own edges (a wall standing on a floor's edge, a mesh's folds)
    // cut nothing; unless one has its solid side inwards (the piece may lie under a block),
    // no arrangement is needed.
    auto alongEdge = [&](const ContactLine2& line) {
      for (const auto& ring : original[r].rings)
        for (size_t k = 0; k < ring.size(); ++k) {
          glm::dvec2 a = piece.frame.project(table[ring[k]]);
          glm::dvec2 d = piece.frame.project(table[ring[(k + 1) % ring.size()]]) - a;
          auto off = [&](const glm::dvec2& q) {
            double t = std::clamp(glm::dot(q - a, d) / glm::dot(d, d), 0.0, 1.0);
            return glm::length(a + d * t - q);
          };
          if (off(line.a) <= tolerance && off(line.b) <= tolerance) return true;
        }
      return false;
    };
    out.contactLines += int(lines.size());
    auto solidInwards = [&](const ContactLine2& line) {
      if (line.solid == 0) return false;
      const glm::dvec2 d = line.b - line.a, left(-d.y, d.x);
      const glm::dvec2 probe = (line.a + line.b) * 0.5 + left * (1e-3 * line.solid);
      return insideOrOn(table, original[r], piece.frame.lift(probe), 0.0);
    };
    if (std::all_of(lines.begin(), lines.end(), alongEdge) &&
        std::none_of(lines.begin(), lines.end(), solidInwards))
      continue;
    Polygon2 poly;
    for (const auto& ring : piece.rings) {
      poly.rings.emplace_back();
      for (int id : ring) poly.rings.back().push_back(piece.frame.project(table[id]));
      poly.ids.push_back(ring);
    }
    ContactCut cut = cutAlongContacts(poly, lines);
    auto idOf = [&](const glm::dvec2& q, int id) {
      return id >= 0 ? id : snap(piece.frame.lift(q), int(r), int(r));
    };
    piece.rings.clear();
    for (size_t k = 0; k < cut.kept.rings.size(); ++k) {
      std::vector<int> ring;
      const size_t m = cut.kept.rings[k].size();
      for (size_t i = 0; i < m; ++i) {
        int id = idOf(cut.kept.rings[k][i], cut.kept.ids[k][i]);
        if (ring.empty() || ring.back() != id) ring.push_back(id);
      }
      for (size_t i = 0; i < m; ++i)
        if (cut.contactEdge[k][i]) {
          int p = idOf(cut.kept.rings[k][i], cut.kept.ids[k][i]);
          int q = idOf(cut.kept.rings[k][(i + 1) % m], cut.kept.ids[k][(i + 1) % m]);
          if (p != q) across.insert(std::minmax(p, q));
        }
      while (ring.size() > 1 && ring.back() == ring.front()) ring.pop_back();
      if (ring.size() >= 3) piece.rings.push_back(std::move(ring));
    }
    for (size_t k = 0; k < cut.kept.lines.size(); ++k) {
      int p = idOf(cut.kept.lines[k][0], cut.kept.lineIds[k][0]);
      int q = idOf(cut.kept.lines[k][1], cut.kept.lineIds[k][1]);
      if (p != q) {
        piece.lines.push_back({p, q});
        across.insert(std::minmax(p, q));
      }
    }
    double pieceArea = 0;
    for (const auto& ring : poly.rings)
      for (size_t k = 0; k < ring.size(); ++k)
        pieceArea += 0.5 * (ring[k].x * ring[(k + 1) % ring.size()].y - ring[(k + 1) % ring.size()].x * ring[k].y);
    for (const auto& removed : cut.removed) {
      if (removed.area <= kNegligibleCut * std::abs(pieceArea)) continue;  // a sliver between lines
      CutAway c{piece.surface, removed.area, {}};
      for (int k : removed.by) c.enclosedBy.push_back(from[size_t(k)]);
      std::sort(c.enclosedBy.begin(), c.enclosedBy.end());
      c.enclosedBy.erase(std::unique(c.enclosedBy.begin(), c.enclosedBy.end()), c.enclosedBy.end());
      out.cutAway.push_back(std::move(c));
    }
    gone[r] = piece.rings.empty();
  }
  size_t kept = 0;
  for (size_t p = 0; p < n; ++p)
    if (!gone[p]) {
      if (kept != p) {
        pieces[kept] = std::move(pieces[p]);
        wheres[kept] = std::move(wheres[p]);
      }
      ++kept;
    }
  pieces.resize(kept);
  wheres.resize(kept);
}

}  // namespace

PatchMesh::PatchMesh() {
  mesh.add_property(surface_, "surface");
  mesh.add_property(side_, "side");
  mesh.add_property(patch_, "patch");
  mesh.add_property(base_, "base");
  mesh.add_property(area_, "area");
  mesh.add_property(reflectance_, "reflectance");
  mesh.add_property(emission_, "emission");
}

bool PatchMesh::emits(int p) const {
  for (int e : patches[size_t(p)].elements) {
    const glm::dvec3 E = emission(e);
    if (E.x > 0 || E.y > 0 || E.z > 0) return true;
  }
  return false;
}

glm::dvec3 PatchMesh::centroid(int e) const {
  auto c = corners(e);
  return (c[0] + c[1] + c[2]) / 3.0;
}

std::array<glm::dvec3, 3> PatchMesh::corners(int e) const {
  std::array<glm::dvec3, 3> out;
  int k = 0;
  for (auto v : mesh.fv_range(face(e))) out[k++] = toGlm(mesh.point(v));
  return out;
}

void PatchMesh::setElement(int e, int surface, int side, double area,
                           const glm::dvec3& reflectance, const glm::dvec3& emission,
                           const glm::dvec3& normal) {
  auto f = face(e);
  mesh.property(surface_, f) = surface;
  mesh.property(side_, f) = side;
  mesh.property(base_, f) = e;
  mesh.property(area_, f) = area;
  mesh.property(reflectance_, f) = toOpenMesh(reflectance);
  mesh.property(emission_, f) = toOpenMesh(emission);
  mesh.set_normal(f, toOpenMesh(normal));
}

PatchMesh buildPatchMesh(const Scene& scene, const MeshSettings& settings) {
  RAD_CHECK(settings.maxElementEdge > 0);
  RAD_CHECK(settings.maxPatchEdge > 0);
  PatchMesh out;
  out.surfaces.resize(scene.surfaces.size());
  PointTable table;
  std::vector<std::string> wheres;
  std::vector<Piece> pieces = planarPieces(scene, table, wheres, out.warnings);
  double tolerance = kOnEdgeTolerance * scene.diagonal();
  std::set<std::pair<int, int>> across;
  if (settings.cutContacts)
    cutAtContacts(scene, table, pieces, wheres, kContactTolerance * scene.diagonal(), across, out);

  int rounds = 0;
  PieceMesher mesher(table, pieces, settings.maxElementEdge, tolerance, wheres, across,
                     settings.contactGrading);
  auto elementTriangles = mesher.run(rounds);
  out.stats.rounds = rounds;
  if (mesher.unresolvedPoints())
    out.warnings.push_back("meshing: " + std::to_string(mesher.unresolvedPoints()) +
                           " boundary points could not be shared with the neighbouring surface");
  std::vector<std::vector<std::vector<int>>> patchesOfPiece(pieces.size());
  for (size_t p = 0; p < pieces.size(); ++p)
    patchesOfPiece[p] = growPatches(table, pieces[p].frame, elementTriangles[p],
                                    settings.maxPatchEdge);

  // Build the OpenMesh mesh, one vertex set per surface side.
  std::vector<std::vector<int>> piecesOfSurface(scene.surfaces.size());
  for (size_t p = 0; p < pieces.size(); ++p) piecesOfSurface[pieces[p].surface].push_back(int(p));
  int nonManifold = 0;
  for (size_t s = 0; s < scene.surfaces.size(); ++s) {
    const Surface& surface = scene.surfaces[s];
    const Material& material = scene.materials[surface.material];
    for (int side = 0; side < (surface.twoSided ? 2 : 1); ++side) {
      std::unordered_map<int, TriMesh::VertexHandle> vertexOf;
      auto vertex = [&](int id) -> TriMesh::VertexHandle {
        auto it = vertexOf.find(id);
        if (it != vertexOf.end()) return it->second;
        auto v = out.mesh.add_vertex(PatchMesh::toOpenMesh(table[id]));
        vertexOf[id] = v;
        return v;
      };
      for (int piece : piecesOfSurface[s]) {
        for (const auto& group : patchesOfPiece[piece]) {
          Patch patch;
          patch.surface = int(s);
          patch.side = side;
          glm::dvec3 normal = pieces[piece].frame.normal * (side ? -1.0 : 1.0);
          std::vector<int> patchPoints;
          for (int k : group) {
            auto t = elementTriangles[piece][k];
            patchPoints.insert(patchPoints.end(), t.begin(), t.end());
            if (side) std::swap(t[1], t[2]);
            glm::dvec3 a = table[t[0]], b = table[t[1]], c = table[t[2]];
            double area = triangleArea(a, b, c);
            if (!(area > 0)) continue;  // never after Delaunay refinement; never add zero area
            auto f = out.mesh.add_face(vertex(t[0]), vertex(t[1]), vertex(t[2]));
            if (!f.is_valid()) {  // non-manifold input (mesh files): give the face its own corners
              ++nonManifold;
              f = out.mesh.add_face(out.mesh.add_vertex(PatchMesh::toOpenMesh(a)),
                                    out.mesh.add_vertex(PatchMesh::toOpenMesh(b)),
                                    out.mesh.add_vertex(PatchMesh::toOpenMesh(c)));
            }
            int e = f.idx();
            out.setElement(e, int(s), side, area, material.reflectance, material.emission, normal);
            out.setPatch(e, int(out.patches.size()));
            patch.elements.push_back(e);
            patch.area += area;
            patch.centroid += area * (a + b + c) / 3.0;
            out.stats.minAngleDeg = std::min({out.stats.minAngleDeg, angleDeg(a, b, c),
                                              angleDeg(b, c, a), angleDeg(c, a, b)});
            out.stats.maxEdge = std::max({out.stats.maxEdge, glm::length(b - a),
                                          glm::length(c - b), glm::length(a - c)});
          }
          if (patch.elements.empty()) continue;
          patch.centroid /= patch.area;
          patch.normal = normal;
          patch.diameter = diameter(table, convexHull(table, pieces[piece].frame, patchPoints));
          out.stats.maxPatchDiameter = std::max(out.stats.maxPatchDiameter, patch.diameter);
          if (side == 0) out.surfaces[s].area += patch.area;
          out.surfaces[s].elements += int(patch.elements.size());
          out.surfaces[s].patches += 1;
          out.patches.push_back(std::move(patch));
        }
      }
    }
  }
  if (nonManifold)
    out.warnings.push_back("meshing: " + std::to_string(nonManifold) +
                           " faces on non-manifold edges got their own vertices");

  // Vertex normals: area-weighted mean of the adjacent element normals.
  for (auto v : out.mesh.vertices()) {
    OpenMesh::Vec3d n(0, 0, 0);
    for (auto f : out.mesh.vf_range(v)) n += out.mesh.normal(f) * out.area(f.idx());
    out.mesh.set_normal(v, n.normalized());
  }
  return out;
}

}  // namespace rad
