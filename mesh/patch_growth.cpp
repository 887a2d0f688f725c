// Elements ▸ patches: compact groups of neighbouring elements, the shooters.
#include "mesh/patch_growth.h"

#include <algorithm>
#include <map>
#include <queue>
#include <set>

#include <glm/geometric.hpp>

namespace rad::meshing {
namespace {

/// Lexicographic order of 2D points: by x, then y.
bool sweepLess(const glm::dvec2& a, const glm::dvec2& b) {
  return std::make_pair(a.x, a.y) < std::make_pair(b.x, b.y);
}

/// The triangles of a piece as a graph: centres in the frame, edge-neighbours, sweep order.
struct TriangleGraph {
  std::vector<glm::dvec2> centre;
  std::vector<std::vector<int>> neighbours;
  std::vector<int> order;  ///< triangles by centre, along u then v
};

/// The triangles on each edge (point ids, lower first), in edge order.
std::map<std::pair<int, int>, std::vector<int>> trianglesByEdge(const std::vector<std::array<int, 3>>& triangles) {
  std::map<std::pair<int, int>, std::vector<int>> byEdge;
  for (int k = 0; k < int(triangles.size()); ++k)
    for (int i = 0; i < 3; ++i) byEdge[std::minmax(triangles[k][i], triangles[k][(i + 1) % 3])].push_back(k);
  return byEdge;
}

/// Each triangle's neighbours across its edges (seams apart), in the order of the edges' point
/// ids.
std::vector<std::vector<int>> edgeNeighbours(const std::vector<std::array<int, 3>>& triangles,
                                             const EdgeSet& seams) {
  std::vector<std::vector<int>> neighbours(triangles.size());
  for (const auto& [edge, users] : trianglesByEdge(triangles)) {
    if (seams.count(edge)) continue;
    for (int a : users)
      for (int b : users)
        if (a != b) neighbours[a].push_back(b);
  }
  return neighbours;
}

/// The triangles of one piece as a graph (centres in the frame, neighbours, sweep order).
TriangleGraph triangleGraph(const PointTable& table, const PlaneFrame& frame,
                            const std::vector<std::array<int, 3>>& triangles, const EdgeSet& seams) {
  TriangleGraph g;
  for (const auto& t : triangles)
    g.centre.push_back(frame.project((table[t[0]] + table[t[1]] + table[t[2]]) / 3.0));
  g.neighbours = edgeNeighbours(triangles, seams);
  for (int k = 0; k < int(triangles.size()); ++k) g.order.push_back(k);
  std::sort(g.order.begin(), g.order.end(),
            [&](int a, int b) { return sweepLess(g.centre[a], g.centre[b]); });
  return g;
}

/// Whether triangle t may join the patch whose hull corners are `hull`: the patch stays no
/// wider than maxDiameter iff the new corners are within it of each other and of every point
/// of the patch, that is of every hull corner. (The seed always fits: a patch is at least
/// one element, however wide.)
bool fits(const PointTable& table, const std::array<int, 3>& t, const std::vector<int>& hull,
          double maxDiameter) {
  auto within = [&](int a, int b) { return glm::length(table[a] - table[b]) <= maxDiameter; };
  for (int v : t) {
    for (int q : hull)
      if (!within(v, q)) return false;
    if (!hull.empty())
      for (int w : t)
        if (!within(v, w)) return false;
  }
  return true;
}

/// The hull corners of the patch with triangle t added.
std::vector<int> withTriangle(const PointTable& table, const PlaneFrame& frame, std::vector<int> hull,
                              const std::array<int, 3>& t) {
  hull.insert(hull.end(), t.begin(), t.end());
  return convexHull(table, frame, std::move(hull));
}

/// One patch grown from `seed` over free triangles, nearest to the seed first; marks them
/// taken.
std::vector<int> growPatch(const PointTable& table, const PlaneFrame& frame,
                           const std::vector<std::array<int, 3>>& triangles,
                           const TriangleGraph& g, int seed, double maxDiameter,
                           std::vector<bool>& taken) {
  std::vector<int> patch, hull;  // the patch's triangles and the corners of its convex hull
  using Candidate = std::pair<double, int>;  // distance to the seed, triangle
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> frontier;
  std::set<int> queued{seed};
  frontier.push({0.0, seed});
  while (!frontier.empty()) {
    int k = frontier.top().second;
    frontier.pop();
    if (!fits(table, triangles[k], hull, maxDiameter)) continue;
    taken[k] = true;
    patch.push_back(k);
    hull = withTriangle(table, frame, std::move(hull), triangles[k]);
    for (int m : g.neighbours[k])
      if (!taken[m] && queued.insert(m).second)
        frontier.push({glm::length(g.centre[m] - g.centre[seed]), m});
  }
  return patch;
}

}  // namespace

std::vector<int> convexHull(const PointTable& table, const PlaneFrame& frame, std::vector<int> ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (ids.size() < 3) return ids;
  std::vector<glm::dvec2> projected;
  for (int id : ids) projected.push_back(frame.project(table[id]));
  std::vector<int> out;
  for (size_t k : rad::convexHull(projected)) out.push_back(ids[k]);
  return out;
}

double diameter(const PointTable& table, const std::vector<int>& hull) {
  double widest = 0;
  for (size_t i = 0; i < hull.size(); ++i)
    for (size_t j = i + 1; j < hull.size(); ++j)
      widest = std::max(widest, glm::length(table[hull[i]] - table[hull[j]]));
  return widest;
}

std::vector<std::vector<int>> growPatches(const PointTable& table, const PlaneFrame& frame,
                                          const std::vector<std::array<int, 3>>& triangles,
                                          const EdgeSet& seams, double maxDiameter) {
  const TriangleGraph g = triangleGraph(table, frame, triangles, seams);
  std::vector<std::vector<int>> patches;
  std::vector<bool> taken(triangles.size(), false);
  for (int seed : g.order)
    if (!taken[seed])
      patches.push_back(growPatch(table, frame, triangles, g, seed, maxDiameter, taken));
  return patches;
}

}  // namespace rad::meshing
