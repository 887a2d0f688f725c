#include "mesh/scene/readers/coplanar_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

#include "mesh/scene/geometry.h"

namespace rad {
namespace {

/// Faces whose unit normals are closer than this (cosine) may share a plane.
constexpr double kSameFacing = 0.999;

using Edge = std::pair<int, int>;  ///< directed: from corner id, to corner id

/// The faces with their corners as ids (shared by exact position), their planes and which
/// face holds each directed edge.
class FaceGraph {
 public:
  explicit FaceGraph(const std::vector<Polygon>& faces);

  /// The faces of the region grown from `seed` over shared edges: faces in the seed's plane,
  /// facing its way.
  std::vector<int> region(int seed, std::vector<bool>& taken) const;
  /// The region's boundary as closed rings of corners (outer first, then holes); empty when it
  /// touches itself at a corner or is not one polygon.
  std::vector<Ring> boundary(const std::vector<int>& region) const;
  /// Whether face f takes part in merging: no holes, an area.
  bool mergeable(int f) const { return normal_[size_t(f)] != glm::dvec3(0.0); }

 private:
  /// The region's boundary: its directed edges whose reverse is not in it, as the corner each
  /// leads to from the corner it leaves (`next`); false when two leave one corner.
  bool boundaryEdges(const std::vector<int>& region, std::map<int, int>& next) const;
  /// One closed chain of `next`, taken out of it, as a ring (empty when it does not close).
  Ring walk(std::map<int, int>& next) const;
  /// The face across directed edge e of a face (the one holding its reverse), or -1 when the
  /// edge is not shared by exactly two faces.
  int across(const Edge& e) const;
  /// Whether face g lies in the plane of the seed face (within kPlanarity of the distance
  /// from the seed's first corner) and faces its way.
  bool inPlane(int seed, int g) const;

  std::vector<glm::dvec3> points_;
  std::vector<std::vector<int>> corners_;
  std::vector<glm::dvec3> normal_;  ///< unit; zero for a face that is not merged
  std::map<Edge, std::vector<int>> edgeFaces_;
};

FaceGraph::FaceGraph(const std::vector<Polygon>& faces) {
  std::map<std::array<double, 3>, int> ids;
  for (size_t f = 0; f < faces.size(); ++f) {
    corners_.emplace_back();
    for (const auto& p : faces[f].outer) {
      const auto [it, added] = ids.emplace(std::array<double, 3>{p.x, p.y, p.z}, int(points_.size()));
      if (added) points_.push_back(p);
      corners_.back().push_back(it->second);
    }
    const glm::dvec3 n = newellNormal(faces[f].outer);
    const bool flat = faces[f].holes.empty() && glm::length(n) > 0;
    normal_.push_back(flat ? glm::normalize(n) : glm::dvec3(0.0));
    const auto& c = corners_.back();
    for (size_t k = 0; flat && k < c.size(); ++k) edgeFaces_[{c[k], c[(k + 1) % c.size()]}].push_back(int(f));
  }
}

int FaceGraph::across(const Edge& e) const {
  const auto mine = edgeFaces_.find(e), theirs = edgeFaces_.find({e.second, e.first});
  if (mine == edgeFaces_.end() || theirs == edgeFaces_.end()) return -1;
  return mine->second.size() == 1 && theirs->second.size() == 1 ? theirs->second[0] : -1;
}

bool FaceGraph::inPlane(int seed, int g) const {
  const glm::dvec3& n = normal_[size_t(seed)];
  if (glm::dot(n, normal_[size_t(g)]) < kSameFacing) return false;
  const glm::dvec3& origin = points_[size_t(corners_[size_t(seed)][0])];
  for (int id : corners_[size_t(g)]) {
    const glm::dvec3& p = points_[size_t(id)];
    if (std::abs(glm::dot(p - origin, n)) > kPlanarity * glm::length(p - origin)) return false;
  }
  return true;
}

std::vector<int> FaceGraph::region(int seed, std::vector<bool>& taken) const {
  std::vector<int> out{seed};
  taken[size_t(seed)] = true;
  for (size_t i = 0; i < out.size(); ++i) {
    const auto& c = corners_[size_t(out[i])];
    for (size_t k = 0; k < c.size(); ++k) {
      const int g = across({c[k], c[(k + 1) % c.size()]});
      if (g < 0 || taken[size_t(g)] || !mergeable(g) || !inPlane(seed, g)) continue;
      taken[size_t(g)] = true;
      out.push_back(g);
    }
  }
  return out;
}

bool FaceGraph::boundaryEdges(const std::vector<int>& region, std::map<int, int>& next) const {
  std::vector<bool> in(corners_.size(), false);
  for (int f : region) in[size_t(f)] = true;
  for (int f : region) {
    const auto& c = corners_[size_t(f)];
    for (size_t k = 0; k < c.size(); ++k) {
      const Edge e{c[k], c[(k + 1) % c.size()]};
      const int g = across(e);
      if (g >= 0 && in[size_t(g)]) continue;
      if (!next.emplace(e.first, e.second).second) return false;  // it touches itself at a corner
    }
  }
  return true;
}

Ring FaceGraph::walk(std::map<int, int>& next) const {
  Ring ring;
  const int start = next.begin()->first;
  int id = start;
  do {
    const auto to = next.find(id);
    if (to == next.end()) return {};  // a chain that does not close
    ring.push_back(points_[size_t(id)]);
    id = to->second;
    next.erase(to);
  } while (id != start);
  return ring;
}

std::vector<Ring> FaceGraph::boundary(const std::vector<int>& region) const {
  std::map<int, int> next;
  if (!boundaryEdges(region, next)) return {};
  std::vector<Ring> outer, holes;
  const glm::dvec3& n = normal_[size_t(region[0])];
  while (!next.empty()) {
    Ring ring = walk(next);
    const double size = ring.empty() ? 0 : ringDiameter(ring);
    const glm::dvec3 area = ring.empty() ? glm::dvec3(0.0) : newellNormal(ring);
    if (!(glm::length(area) > kMinRelativeArea * size * size)) return {};  // a crack, not a ring
    (glm::dot(area, n) > 0 ? outer : holes).push_back(std::move(ring));
  }
  if (outer.size() != 1) return {};
  outer.insert(outer.end(), holes.begin(), holes.end());
  return outer;
}

/// The polygon of boundary rings: the first outer, the rest holes.
Polygon polygonOf(std::vector<Ring> rings) {
  Polygon p;
  p.outer = std::move(rings[0]);
  p.holes.assign(std::make_move_iterator(rings.begin() + 1), std::make_move_iterator(rings.end()));
  return p;
}

}  // namespace

std::vector<Polygon> mergeCoplanarFaces(const std::vector<Polygon>& faces) {
  const FaceGraph graph(faces);
  std::vector<bool> taken(faces.size(), false);
  std::vector<Polygon> out;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (taken[f]) continue;
    if (!graph.mergeable(int(f))) {
      out.push_back(faces[f]);
      continue;
    }
    const std::vector<int> region = graph.region(int(f), taken);
    std::vector<Ring> rings = region.size() > 1 ? graph.boundary(region) : std::vector<Ring>{};
    if (!rings.empty()) out.push_back(polygonOf(std::move(rings)));
    else for (int g : region) out.push_back(faces[size_t(g)]);
  }
  return out;
}

}  // namespace rad
