#pragma once
// A bounding-box hierarchy over items given as boxes, for searches whose cost should follow
// the items near what they look for, not the scene's volume: the shooters' nearest facing
// elements (radiosity/shooting/point_tree.h) and the elements a hemicube culls and clear sight
// tests (radiosity/formfactors/element_hierarchy.h) are both built here.
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace rad {

/// An axis-aligned box, empty (lo above hi) until a point or a box is added.
struct AlignedBox {
  glm::dvec3 lo{HUGE_VAL}, hi{-HUGE_VAL};

  void add(const glm::dvec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  void add(const AlignedBox& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
  /// Half the surface area (0 for an empty box).
  double halfArea() const {
    if (lo.x > hi.x) return 0;
    const glm::dvec3 d = hi - lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }
};

/// The hierarchy, depth first: nodes[0] is the root, an inner node's first child is the node
/// after it and its second child is nodes[second].
struct BoxTree {
  /// A subtree: the box [lo, hi] around its items, which are order[first, first + count).
  /// A leaf has second == 0.
  struct Node {
    glm::dvec3 lo, hi;
    uint32_t first = 0, count = 0, second = 0;

    bool leaf() const { return second == 0; }
  };

  std::vector<Node> nodes;
  /// The items' indices, each subtree's contiguous.
  std::vector<uint32_t> order;
};

/// How a node's items are parted between its children.
enum class BoxSplit {
  /// At the median centre along the longest side of the centres' box: halves of equal count,
  /// for items of one size (points).
  median,
  /// By the surface area heuristic over 16 bins of the centres along each axis (median splits
  /// where it finds none, and below depth 48, which bounds the depth): for items of many
  /// sizes (elements).
  surfaceArea,
};

/// The hierarchy over items i with box boxes[i] and centre centres[i] (the same count), at
/// most leafSize items to a leaf. No item: no node.
BoxTree buildBoxTree(const std::vector<AlignedBox>& boxes, const std::vector<glm::dvec3>& centres,
                     uint32_t leafSize, BoxSplit split);

}  // namespace rad
