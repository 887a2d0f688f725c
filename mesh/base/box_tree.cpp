// Items ▸ hierarchy: each node's items parted in two, depth first, until a leaf holds few
// enough.
#include "mesh/base/box_tree.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace rad {
namespace {

/// Centroid bins per axis of the surface area heuristic.
constexpr int kBins = 16;
/// Below this depth the heuristic's splits; deeper, median splits keep the depth bounded.
constexpr int kMaxHeuristicDepth = 48;

/// One axis's bins: each bin's item count and the box of their boxes.
struct Bins {
  std::array<AlignedBox, kBins> box;
  std::array<uint32_t, kBins> count{};
};

/// The longest axis of a box: x on a tie with y or z, then y.
int longestAxis(const AlignedBox& b) {
  const glm::dvec3 d = b.hi - b.lo;
  return d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
}

/// Builds the nodes depth first (a node's first child right after it).
struct Builder {
  const std::vector<AlignedBox>& boxes;
  const std::vector<glm::dvec3>& centres;
  uint32_t leafSize;
  BoxSplit rule;
  BoxTree& tree;

  /// The bin of a centre along `axis` of the centres' box c.
  static int bin(const glm::dvec3& centre, const AlignedBox& c, int axis) {
    const double extent = c.hi[axis] - c.lo[axis];
    const int b = int((centre[axis] - c.lo[axis]) / extent * kBins);
    return std::min(std::max(b, 0), kBins - 1);
  }

  /// The surface area heuristic's cost of splitting after bin `split` (left: bins < split).
  static double splitCost(const Bins& bins, int split) {
    AlignedBox left, right;
    uint32_t nLeft = 0, nRight = 0;
    for (int b = 0; b < kBins; ++b) {
      (b < split ? left : right).add(bins.box[size_t(b)]);
      (b < split ? nLeft : nRight) += bins.count[size_t(b)];
    }
    if (nLeft == 0 || nRight == 0) return HUGE_VAL;
    return left.halfArea() * nLeft + right.halfArea() * nRight;
  }

  /// The items of order[first, first + count) binned along each axis of their centres' box c
  /// (none along an axis c is flat on).
  std::array<Bins, 3> binned(uint32_t first, uint32_t count, const AlignedBox& c) const {
    std::array<Bins, 3> bins;
    for (uint32_t i = first; i < first + count; ++i) {
      const uint32_t item = tree.order[i];
      for (int axis = 0; axis < 3; ++axis) {
        if (!(c.hi[axis] > c.lo[axis])) continue;
        const int k = bin(centres[item], c, axis);
        bins[size_t(axis)].box[size_t(k)].add(boxes[item]);
        ++bins[size_t(axis)].count[size_t(k)];
      }
    }
    return bins;
  }

  /// Splits order[first, first + count) by the heuristic's best bin plane; returns the
  /// number of items on the left, or 0 if every centre shares one bin on every axis.
  uint32_t heuristicSplit(uint32_t first, uint32_t count, const AlignedBox& c) {
    const std::array<Bins, 3> bins = binned(first, count, c);
    double best = HUGE_VAL;
    int bestAxis = -1, bestSplit = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (int split = 1; split < kBins && c.hi[axis] > c.lo[axis]; ++split) {
        const double cost = splitCost(bins[size_t(axis)], split);
        if (cost < best) best = cost, bestAxis = axis, bestSplit = split;
      }
    if (bestAxis < 0) return 0;
    auto middle = std::partition(tree.order.begin() + first, tree.order.begin() + first + count,
                                 [&](uint32_t item) { return bin(centres[item], c, bestAxis) < bestSplit; });
    return uint32_t(middle - (tree.order.begin() + first));
  }

  /// Splits order[first, first + count) at the median centre along the longest side of the
  /// centres' box c (equal centres by index, so the split is the same on every platform);
  /// returns the number of items on the left (count / 2).
  uint32_t medianSplit(uint32_t first, uint32_t count, const AlignedBox& c) {
    const int axis = longestAxis(c);
    auto begin = tree.order.begin() + first;
    std::nth_element(begin, begin + count / 2, begin + count, [&](uint32_t a, uint32_t b) {
      return centres[a][axis] < centres[b][axis] || (centres[a][axis] == centres[b][axis] && a < b);
    });
    return count / 2;
  }

  /// Appends the node of order[first, first + count), then its subtrees.
  void build(uint32_t first, uint32_t count, int depth) {
    const size_t index = tree.nodes.size();
    tree.nodes.emplace_back();
    AlignedBox box, c;
    for (uint32_t i = first; i < first + count; ++i) box.add(boxes[tree.order[i]]), c.add(centres[tree.order[i]]);
    tree.nodes[index].lo = box.lo, tree.nodes[index].hi = box.hi;
    tree.nodes[index].first = first, tree.nodes[index].count = count;
    if (count <= leafSize) return;
    const bool heuristic = rule == BoxSplit::surfaceArea && depth < kMaxHeuristicDepth;
    uint32_t left = heuristic ? heuristicSplit(first, count, c) : 0;
    if (left == 0) left = medianSplit(first, count, c);
    build(first, left, depth + 1);
    tree.nodes[index].second = uint32_t(tree.nodes.size());
    build(first + left, count - left, depth + 1);
  }
};

}  // namespace

BoxTree buildBoxTree(const std::vector<AlignedBox>& boxes, const std::vector<glm::dvec3>& centres,
                     uint32_t leafSize, BoxSplit split) {
  BoxTree tree;
  tree.order.resize(boxes.size());
  std::iota(tree.order.begin(), tree.order.end(), 0u);
  if (boxes.empty()) return tree;
  tree.nodes.reserve(4 * boxes.size() / leafSize + 1);
  Builder{boxes, centres, leafSize, split, tree}.build(0, uint32_t(boxes.size()), 0);
  return tree;
}

}  // namespace rad
