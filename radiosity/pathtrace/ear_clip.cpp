#include "radiosity/pathtrace/ear_clip.h"

#include <cmath>
#include <numeric>

namespace rad::pathtrace {
namespace {

/// Twice the signed area of triangle (o, a, b): positive when it turns counter-clockwise.
double cross2(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/// Whether p lies strictly inside the counter-clockwise triangle (a, b, c).
bool insideTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return cross2(a, b, p) > 0 && cross2(b, c, p) > 0 && cross2(c, a, p) > 0;
}

/// The unsigned angle at `at` between the directions to p and to q.
double angleAt(const glm::dvec2& p, const glm::dvec2& at, const glm::dvec2& q) {
  const glm::dvec2 u = p - at, v = q - at;
  return std::atan2(std::abs(u.x * v.y - u.y * v.x), u.x * v.x + u.y * v.y);
}

/// Whether no other corner of the ring lies inside triangle (p, c, q).
bool emptyTriangle(const std::vector<glm::dvec2>& pts, const std::vector<int>& ring, int p, int c, int q) {
  for (const int k : ring)
    if (k != p && k != c && k != q && insideTriangle(pts[k], pts[p], pts[c], pts[q])) return false;
  return true;
}

/// The corner of the ring to clip: the first ear, else the most convex corner.
size_t nextEar(const std::vector<glm::dvec2>& pts, const std::vector<int>& ring) {
  const size_t n = ring.size();
  int best = -1;
  double bestTurn = -HUGE_VAL;
  for (size_t i = 0; i < n; ++i) {
    const int p = ring[(i + n - 1) % n], c = ring[i], q = ring[(i + 1) % n];
    const double turn = cross2(pts[p], pts[c], pts[q]);
    if (turn > bestTurn) bestTurn = turn, best = int(i);
    if (turn <= 0) continue;
    if (emptyTriangle(pts, ring, p, c, q)) return i;
  }
  return size_t(best);
}

/// A convex quad's two triangles, or none when the quad is not convex. A quad (a bent wall is
/// one) takes its Delaunay diagonal: the angles facing it sum to at most π. The same polygon
/// meshed elsewhere then bends along the same line.
std::vector<std::array<int, 3>> quadTriangles(const std::vector<glm::dvec2>& pts) {
  if (cross2(pts[0], pts[1], pts[2]) > 0 && cross2(pts[2], pts[3], pts[0]) > 0 &&
      angleAt(pts[0], pts[1], pts[2]) + angleAt(pts[2], pts[3], pts[0]) <= 3.14159265358979323846)
    return {{0, 1, 2}, {0, 2, 3}};
  if (cross2(pts[1], pts[2], pts[3]) > 0 && cross2(pts[3], pts[0], pts[1]) > 0) return {{1, 2, 3}, {1, 3, 0}};
  return {};
}

}  // namespace

std::vector<std::array<int, 3>> earClip(const std::vector<glm::dvec2>& pts) {
  if (pts.size() == 4)
    if (auto quad = quadTriangles(pts); !quad.empty()) return quad;
  std::vector<int> ring(pts.size());
  std::iota(ring.begin(), ring.end(), 0);
  std::vector<std::array<int, 3>> out;
  while (ring.size() > 3) {
    const size_t n = ring.size(), i = nextEar(pts, ring);
    out.push_back({ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]});
    ring.erase(ring.begin() + long(i));
  }
  if (ring.size() == 3) out.push_back({ring[0], ring[1], ring[2]});
  return out;
}

}  // namespace rad::pathtrace
