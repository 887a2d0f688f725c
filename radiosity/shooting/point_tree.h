#pragma once
// A bounding-volume hierarchy over points (mesh/base/box_tree.h), for "the nearest point that
// passes a test, within a reach of a box": its cost follows the points near the box, not the
// box's volume, whatever the spread of sizes in the scene (a grid's cells would be too coarse
// for small things or too many for large ones).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "mesh/base/box_tree.h"

namespace rad {

class PointTree {
 public:
  /// At most this many points in a leaf.
  static constexpr uint32_t kLeafSize = 8;

  /// The tree over `points` (each its own box and centre).
  explicit PointTree(std::vector<glm::dvec3> points) : points_(std::move(points)) {
    std::vector<AlignedBox> boxes;
    boxes.reserve(points_.size());
    for (const glm::dvec3& p : points_) boxes.push_back({p, p});
    tree_ = buildBoxTree(boxes, points_, kLeafSize, BoxSplit::median);
  }

  /// The points, by index.
  const std::vector<glm::dvec3>& points() const { return points_; }

  /// The smallest distance(i) over the points, if under `reach` (HUGE_VAL otherwise).
  /// `distance` returns HUGE_VAL for a point that does not count; it must never be less than
  /// the point's distance to the box [lo, hi], so that subtrees farther from the box than the
  /// best found so far are skipped.
  template <class Distance>
  double nearest(const glm::dvec3& lo, const glm::dvec3& hi, double reach, Distance&& distance) const {
    if (tree_.nodes.empty()) return HUGE_VAL;
    double best = reach;
    uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = tree_.nodes[stack[--top]];
      if (boxDistance(node, lo, hi) >= best) continue;
      if (node.leaf()) {
        for (uint32_t k = node.first; k < node.first + node.count; ++k)
          best = std::min(best, distance(int(tree_.order[k])));
        continue;
      }
      const uint32_t first = uint32_t(&node - tree_.nodes.data()) + 1, second = node.second;
      // The nearer child last, so it is visited first.
      const bool firstNearer =
          boxDistance(tree_.nodes[first], lo, hi) <= boxDistance(tree_.nodes[second], lo, hi);
      stack[top++] = firstNearer ? second : first;
      stack[top++] = firstNearer ? first : second;
    }
    return best < reach ? best : HUGE_VAL;
  }

 private:
  using Node = BoxTree::Node;

  static double boxDistance(const Node& n, const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 gap = glm::max(glm::max(n.lo - hi, lo - n.hi), glm::dvec3(0.0));
    return std::sqrt(gap.x * gap.x + gap.y * gap.y + gap.z * gap.z);
  }

  std::vector<glm::dvec3> points_;
  /// Median splits along the longest side: depth about log2(n / kLeafSize), far within the
  /// traversal's stack.
  BoxTree tree_;
};

}  // namespace rad
