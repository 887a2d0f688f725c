// Polygons ▸ rays: a hierarchy of boxes split at the median along their widest axis; a ray
// visits the boxes it crosses nearer than its best hit, and meets a polygon where it crosses
// its plane inside its rings (even-odd).
#include "mesh/surface_rays.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

namespace rad {
namespace {

/// A polygon's box is widened by this times its size plus its distance from the origin, so that
/// round-off in a hit point (a flat box for a polygon along an axis) does not lose the hit.
constexpr double kBoxSlack = 1e-9;
/// Polygons per leaf of the hierarchy.
constexpr int kLeafPolygons = 4;

/// Even-odd over the outer ring and the holes: whether p, on the frame's plane, is inside.
bool insidePolygon(const PlaneFrame& frame, const Polygon& polygon, const glm::dvec3& p) {
  bool inside = insideRing(frame, polygon.outer, p);
  for (const Ring& hole : polygon.holes) inside = inside != insideRing(frame, hole, p);
  return inside;
}

/// The distance along the ray (origin o, direction d, its inverse `inverse`) at which it enters
/// the box [lo, hi], or infinity when it misses it. An axis the ray does not move along is
/// tested apart, where 0 · ∞ would give NaN.
double entry(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& o, const glm::dvec3& d,
             const glm::dvec3& inverse) {
  double in = 0, out = HUGE_VAL;
  for (int axis = 0; axis < 3; ++axis) {
    if (d[axis] == 0) {
      if (o[axis] < lo[axis] || o[axis] > hi[axis]) return HUGE_VAL;
      continue;
    }
    const double a = (lo[axis] - o[axis]) * inverse[axis], b = (hi[axis] - o[axis]) * inverse[axis];
    in = std::max(in, std::min(a, b)), out = std::min(out, std::max(a, b));
  }
  return in <= out ? in : HUGE_VAL;
}

}  // namespace

SurfaceRays::SurfaceRays(const std::vector<Polygon>& polygons, const std::vector<bool>& twoSided)
    : polygons_(polygons) {
  for (size_t i = 0; i < polygons.size(); ++i) {
    Target target{planeFrame(polygons[i].outer), glm::dvec3(HUGE_VAL), glm::dvec3(-HUGE_VAL), twoSided[i]};
    for (const glm::dvec3& p : polygons[i].outer) target.lo = glm::min(target.lo, p), target.hi = glm::max(target.hi, p);
    const double size = glm::length(target.hi - target.lo);
    const double reach = size + glm::length(glm::max(glm::abs(target.lo), glm::abs(target.hi)));
    target.lo -= glm::dvec3(kBoxSlack * reach), target.hi += glm::dvec3(kBoxSlack * reach);
    if (glm::length(newellNormal(polygons[i].outer)) <= kMinRelativeArea * size * size)
      target.frame.normal = glm::dvec3(0.0);  // never met
    targets_.push_back(target);
  }
  order_.resize(targets_.size());
  std::iota(order_.begin(), order_.end(), 0);
  if (!targets_.empty()) addNode(0, int(targets_.size()));
}

/// Adds the node over order_[begin, end) and, above kLeafPolygons, its two halves (the median of
/// the box centres along the node's widest axis). Returns its index.
int SurfaceRays::addNode(int begin, int end) {
  Node node{glm::dvec3(HUGE_VAL), glm::dvec3(-HUGE_VAL), begin, end};
  for (int k = begin; k < end; ++k) {
    node.lo = glm::min(node.lo, targets_[size_t(order_[size_t(k)])].lo);
    node.hi = glm::max(node.hi, targets_[size_t(order_[size_t(k)])].hi);
  }
  const int index = int(nodes_.size());
  nodes_.push_back(node);
  if (end - begin <= kLeafPolygons) return index;
  const glm::dvec3 size = node.hi - node.lo;
  const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
  const auto centre = [&](int i) { return targets_[size_t(i)].lo[axis] + targets_[size_t(i)].hi[axis]; };
  const int middle = (begin + end) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int a, int b) { return centre(a) < centre(b); });
  const int left = addNode(begin, middle), right = addNode(middle, end);
  nodes_[size_t(index)].children[0] = left, nodes_[size_t(index)].children[1] = right;
  return index;
}

/// Whether the ray meets polygon i nearer than t (updated when it does).
bool SurfaceRays::meets(int i, const Ray& ray, double& t) const {
  const Target& target = targets_[size_t(i)];
  const double across = glm::dot(target.frame.normal, ray.dir);
  if (across == 0 || (ray.throughBacks && !target.twoSided && across > 0)) return false;
  const double s = glm::dot(target.frame.normal, target.frame.origin - ray.origin) / across;
  if (!(s > ray.after && s < t)) return false;
  const glm::dvec3 p = ray.origin + s * ray.dir;
  if (glm::any(glm::lessThan(p, target.lo)) || glm::any(glm::greaterThan(p, target.hi))) return false;
  if (!insidePolygon(target.frame, polygons_[size_t(i)], p)) return false;
  t = s;
  return true;
}

/// The hit on polygon i at t: its front when the ray comes against its normal.
RayHit SurfaceRays::hit(int i, const Ray& ray, double t) const {
  const Target& target = targets_[size_t(i)];
  return {t, i, target.twoSided || glm::dot(target.frame.normal, ray.dir) < 0};
}

/// Updates `best` with the polygons of the node's subtree the ray meets nearer.
void SurfaceRays::search(int index, const Ray& ray, std::optional<RayHit>& best) const {
  const Node& node = nodes_[size_t(index)];
  double t = best ? best->t : HUGE_VAL;
  if (!(entry(node.lo, node.hi, ray.origin, ray.dir, ray.inverse) < t)) return;
  if (node.children[0] < 0) {
    for (int k = node.begin; k < node.end; ++k)
      if (meets(order_[size_t(k)], ray, t)) best = hit(order_[size_t(k)], ray, t);
    return;
  }
  for (int child : node.children) search(child, ray, best);
}

std::optional<RayHit> SurfaceRays::firstHit(const glm::dvec3& origin, const glm::dvec3& dir,
                                            bool throughBacks, double after) const {
  std::optional<RayHit> best;
  if (!nodes_.empty()) search(0, Ray{origin, dir, 1.0 / dir, throughBacks, after}, best);
  return best;
}

}  // namespace rad
