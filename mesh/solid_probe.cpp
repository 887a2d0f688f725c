// Planar pieces ▸ rays: the first piece a ray meets, through a hierarchy of boxes, and the
// vote of a hemisphere of rays on whether a point is inside a solid.
#include "mesh/solid_probe.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

namespace rad::meshing {
namespace {

/// Rays start this far off the surface, times the scene diagonal (ten times the contact
/// tolerance: clear of round-off, well inside any wall a building has).
constexpr double kRayOffset = 1e-4;
/// The hemisphere's rays: kRaySide × kRaySide strata of a cosine-spread hemisphere, one ray
/// at the middle of each (fixed, so the answer does not depend on a seed).
constexpr int kRaySide = 8;
/// Pieces per leaf of the hierarchy.
constexpr int kLeafSize = 4;

/// Whether the ray (origin o, direction with inverse `inv`) meets the box before `tMax`.
bool rayMeetsBox(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& o,
                 const glm::dvec3& inv, double tMax) {
  const glm::dvec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
  const glm::dvec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
  const double enter = std::max({near.x, near.y, near.z, 0.0});
  const double leave = std::min({far.x, far.y, far.z, tMax});
  return enter <= leave;
}

/// Even-odd: whether x lies inside the rings.
bool insideRings(const Polygon2& poly, const glm::dvec2& x) {
  bool inside = false;
  for (const auto& ring : poly.rings)
    for (size_t k = 0; k < ring.size(); ++k) {
      const glm::dvec2 &a = ring[k], &b = ring[(k + 1) % ring.size()];
      if ((a.y > x.y) != (b.y > x.y) && x.x < a.x + (x.y - a.y) * (b.x - a.x) / (b.y - a.y))
        inside = !inside;
    }
  return inside;
}

/// Two unit vectors that make a right-handed frame with n.
std::pair<glm::dvec3, glm::dvec3> tangents(const glm::dvec3& n) {
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(helper, n));
  return {t, glm::cross(n, t)};
}

}  // namespace

SolidProbe::SolidProbe(const Scene& scene, const PointTable& table, const std::vector<Piece>& pieces)
    : offset_(kRayOffset * scene.diagonal()) {
  for (const Piece& piece : pieces) {
    frames_.push_back(piece.frame);
    rings_.push_back(projectedRings(table, piece));
    twoSided_.push_back(scene.surfaces[size_t(piece.surface)].twoSided);
    glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
    for (const auto& ring : piece.rings)
      for (int id : ring) lo = glm::min(lo, table[id]), hi = glm::max(hi, table[id]);
    lo_.push_back(lo);
    hi_.push_back(hi);
  }
  order_.resize(pieces.size());
  std::iota(order_.begin(), order_.end(), 0);
  if (!pieces.empty()) build(0, int(pieces.size()));
}

/// Builds the node over order_[first, first + count): a leaf when small, else split at the
/// median of the box centres along the widest axis. Returns the node's index.
int SolidProbe::build(int first, int count) {
  const int index = int(nodes_.size());
  nodes_.push_back({glm::dvec3(HUGE_VAL), glm::dvec3(-HUGE_VAL)});
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (int k = first; k < first + count; ++k)
    lo = glm::min(lo, lo_[size_t(order_[size_t(k)])]), hi = glm::max(hi, hi_[size_t(order_[size_t(k)])]);
  nodes_[size_t(index)].lo = lo, nodes_[size_t(index)].hi = hi;
  if (count <= kLeafSize) {
    nodes_[size_t(index)].first = first, nodes_[size_t(index)].count = count;
    return index;
  }
  const glm::dvec3 extent = hi - lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  auto begin = order_.begin() + first, middle = begin + count / 2;
  std::nth_element(begin, middle, begin + count, [&](int a, int b) {
    return lo_[size_t(a)][axis] + hi_[size_t(a)][axis] < lo_[size_t(b)][axis] + hi_[size_t(b)][axis];
  });
  build(first, count / 2);
  const int right = build(first + count / 2, count - count / 2);
  nodes_[size_t(index)].right = right;
  return index;
}

/// Whether the ray meets piece `piece` nearer than t (updated when it does).
bool SolidProbe::hitsPiece(int piece, const glm::dvec3& origin, const glm::dvec3& dir, double& t) const {
  const PlaneFrame& f = frames_[size_t(piece)];
  const double across = glm::dot(f.normal, dir);
  if (std::abs(across) < 1e-12) return false;  // along the plane
  const double s = glm::dot(f.normal, f.origin - origin) / across;
  if (s <= 0 || s >= t || !insideRings(rings_[size_t(piece)], f.project(origin + s * dir))) return false;
  t = s;
  return true;
}

/// Tests the ray against the pieces of leaf `node`.
void SolidProbe::hitLeaf(const Node& node, const glm::dvec3& origin, const glm::dvec3& dir, Hit& best) const {
  for (int k = node.first; k < node.first + node.count; ++k)
    if (hitsPiece(order_[size_t(k)], origin, dir, best.t)) best.piece = order_[size_t(k)];
}

/// The nearest piece the ray meets, if any (piece -1).
SolidProbe::Hit SolidProbe::firstHit(const glm::dvec3& origin, const glm::dvec3& dir) const {
  Hit best{-1, HUGE_VAL};
  if (nodes_.empty()) return best;
  const glm::dvec3 inv = 1.0 / dir;  // infinities along axes the ray does not move on
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& node = nodes_[size_t(stack.back())];
    const int index = stack.back();
    stack.pop_back();
    if (!rayMeetsBox(node.lo, node.hi, origin, inv, best.t)) continue;
    if (node.count > 0) {
      hitLeaf(node, origin, dir, best);
      continue;
    }
    stack.push_back(node.right);
    stack.push_back(index + 1);
  }
  return best;
}

bool SolidProbe::insideSolid(const glm::dvec3& p, const glm::dvec3& normal) const {
  const auto [t, b] = tangents(normal);
  const glm::dvec3 origin = p + offset_ * normal;
  int backs = 0;
  for (int i = 0; i < kRaySide; ++i)
    for (int j = 0; j < kRaySide; ++j) {
      const double u = (i + 0.5) / kRaySide, phi = 2 * M_PI * (j + 0.5) / kRaySide;
      const double r = std::sqrt(u);
      const glm::dvec3 dir = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(1 - u) * normal;
      const Hit hit = firstHit(origin, dir);
      if (hit.piece >= 0 && !twoSided_[size_t(hit.piece)] &&
          glm::dot(frames_[size_t(hit.piece)].normal, dir) > 0)
        ++backs;
    }
  return 2 * backs > kRaySide * kRaySide;
}

}  // namespace rad::meshing
