#pragma once
// A bounding-volume hierarchy over points, for "the nearest point that passes a test, within a
// reach of a box": its cost follows the points near the box, not the box's volume, whatever
// the spread of sizes in the scene (a grid's cells would be too coarse for small things or too
// many for large ones).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace rad {

class PointTree {
 public:
  /// At most this many points in a leaf.
  static constexpr uint32_t kLeafSize = 8;

  explicit PointTree(std::vector<glm::dvec3> points) : points_(std::move(points)) {
    order_.resize(points_.size());
    for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
    if (!points_.empty()) build(0, uint32_t(points_.size()));
  }

  /// The smallest distance(i) over the points, if under `reach` (HUGE_VAL otherwise).
  /// `distance` returns HUGE_VAL for a point that does not count; it must never be less than
  /// the point's distance to the box [lo, hi], so that subtrees farther from the box than the
  /// best found so far are skipped.
  const std::vector<glm::dvec3>& points() const { return points_; }

  template <class Distance>
  double nearest(const glm::dvec3& lo, const glm::dvec3& hi, double reach, Distance&& distance) const {
    if (nodes_.empty()) return HUGE_VAL;
    double best = reach;
    uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (boxDistance(node, lo, hi) >= best) continue;
      if (node.second == 0) {
        for (uint32_t k = node.first; k < node.first + node.count; ++k) best = std::min(best, distance(int(order_[k])));
        continue;
      }
      const uint32_t first = uint32_t(&node - nodes_.data()) + 1, second = node.second;
      // The nearer child last, so it is visited first.
      const bool firstNearer = boxDistance(nodes_[first], lo, hi) <= boxDistance(nodes_[second], lo, hi);
      stack[top++] = firstNearer ? second : first;
      stack[top++] = firstNearer ? first : second;
    }
    return best < reach ? best : HUGE_VAL;
  }

 private:
  /// A subtree: the box around its points, order_[first, first + count); a leaf has
  /// second == 0, an inner node's first child follows it and its second is nodes_[second].
  struct Node {
    glm::dvec3 lo, hi;
    uint32_t first = 0, count = 0, second = 0;
  };

  static double boxDistance(const Node& n, const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 gap = glm::max(glm::max(n.lo - hi, lo - n.hi), glm::dvec3(0.0));
    return std::sqrt(gap.x * gap.x + gap.y * gap.y + gap.z * gap.z);
  }

  /// Median splits along the longest side: depth about log2(n / kLeafSize), far within the
  /// traversal's stack.
  uint32_t build(uint32_t first, uint32_t count) {
    const uint32_t index = uint32_t(nodes_.size());
    nodes_.push_back({glm::dvec3(HUGE_VAL), glm::dvec3(-HUGE_VAL), first, count, 0});
    glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
    for (uint32_t k = first; k < first + count; ++k) {
      lo = glm::min(lo, points_[order_[k]]);
      hi = glm::max(hi, points_[order_[k]]);
    }
    nodes_[index].lo = lo;
    nodes_[index].hi = hi;
    if (count <= kLeafSize) return index;
    const glm::dvec3 side = hi - lo;
    const int axis = side.x >= side.y && side.x >= side.z ? 0 : side.y >= side.z ? 1 : 2;
    const uint32_t half = count / 2;
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](uint32_t a, uint32_t b) { return points_[a][axis] < points_[b][axis]; });
    build(first, half);
    const uint32_t second = build(first + half, count - half);
    nodes_[index].second = second;
    return index;
  }

  std::vector<glm::dvec3> points_;
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace rad
