#include "radiosity/formfactors/element_hierarchy.h"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>

#include <glm/common.hpp>

#include "mesh/base/error.h"

namespace rad {
namespace {

/// Centroid bins per axis of the surface area heuristic.
constexpr int kBins = 16;
/// Below this depth the heuristic's splits; deeper, median splits keep the depth bounded.
constexpr int kMaxHeuristicDepth = 48;

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};

  void add(const glm::dvec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  void add(const Box& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
  /// Half the surface area (0 for an empty box).
  double halfArea() const {
    if (lo.x > hi.x) return 0;
    const glm::dvec3 d = hi - lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }
};

/// One axis's bins: each bin's element count and the box of their corners.
struct Bins {
  std::array<Box, kBins> box;
  std::array<uint32_t, kBins> count{};
};

/// Builds the nodes depth first (a node's first child right after it).
struct Builder {
  const std::vector<glm::dvec3>& positions;
  const std::vector<uint32_t>& indices;
  std::vector<ElementHierarchy::Node>& nodes;
  std::vector<uint32_t>& order;
  std::vector<glm::dvec3> centroids;

  /// The box of element e's corners.
  Box elementBox(uint32_t e) const {
    Box b;
    for (int k = 0; k < 3; ++k) b.add(positions[indices[3 * size_t(e) + k]]);
    return b;
  }

  /// The centroid bin of element e along `axis` of the centroid box c.
  static int bin(const glm::dvec3& centroid, const Box& c, int axis) {
    const double extent = c.hi[axis] - c.lo[axis];
    const int b = int((centroid[axis] - c.lo[axis]) / extent * kBins);
    return std::min(std::max(b, 0), kBins - 1);
  }

  /// The surface area heuristic's cost of splitting after bin `split` (left: bins < split).
  static double splitCost(const Bins& bins, int split) {
    Box left, right;
    uint32_t nLeft = 0, nRight = 0;
    for (int b = 0; b < kBins; ++b) {
      (b < split ? left : right).add(bins.box[size_t(b)]);
      (b < split ? nLeft : nRight) += bins.count[size_t(b)];
    }
    if (nLeft == 0 || nRight == 0) return std::numeric_limits<double>::infinity();
    return left.halfArea() * nLeft + right.halfArea() * nRight;
  }

  /// Splits order[first, first + count) by the heuristic's best bin plane; returns the
  /// number of elements on the left, or 0 if every centroid shares one bin on every axis.
  uint32_t heuristicSplit(uint32_t first, uint32_t count, const Box& c) {
    std::array<Bins, 3> bins;
    for (uint32_t i = first; i < first + count; ++i) {
      const uint32_t e = order[i];
      const Box b = elementBox(e);
      for (int axis = 0; axis < 3; ++axis) {
        if (!(c.hi[axis] > c.lo[axis])) continue;
        const int k = bin(centroids[e], c, axis);
        bins[size_t(axis)].box[size_t(k)].add(b);
        ++bins[size_t(axis)].count[size_t(k)];
      }
    }
    double best = std::numeric_limits<double>::infinity();
    int bestAxis = -1, bestSplit = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (int split = 1; split < kBins && c.hi[axis] > c.lo[axis]; ++split) {
        const double cost = splitCost(bins[size_t(axis)], split);
        if (cost < best) best = cost, bestAxis = axis, bestSplit = split;
      }
    if (bestAxis < 0) return 0;
    auto middle = std::partition(order.begin() + first, order.begin() + first + count, [&](uint32_t e) {
      return bin(centroids[e], c, bestAxis) < bestSplit;
    });
    return uint32_t(middle - (order.begin() + first));
  }

  /// Splits order[first, first + count) at the median centroid along the centroid box's
  /// longest axis; returns the number of elements on the left (count / 2).
  uint32_t medianSplit(uint32_t first, uint32_t count, const Box& c) {
    const glm::dvec3 d = c.hi - c.lo;
    const int axis = d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
    auto begin = order.begin() + first;
    std::nth_element(begin, begin + count / 2, begin + count, [&](uint32_t a, uint32_t b) {
      return centroids[a][axis] < centroids[b][axis] || (centroids[a][axis] == centroids[b][axis] && a < b);
    });
    return count / 2;
  }

  /// Appends the node of order[first, first + count), then its subtrees.
  void build(uint32_t first, uint32_t count, int depth) {
    const size_t index = nodes.size();
    nodes.emplace_back();
    Box box, c;
    for (uint32_t i = first; i < first + count; ++i) box.add(elementBox(order[i])), c.add(centroids[order[i]]);
    nodes[index].lo = box.lo, nodes[index].hi = box.hi;
    nodes[index].first = first, nodes[index].count = count;
    if (count <= ElementHierarchy::kLeafSize) return;
    uint32_t left = depth < kMaxHeuristicDepth ? heuristicSplit(first, count, c) : 0;
    if (left == 0) left = medianSplit(first, count, c);
    build(first, left, depth + 1);
    nodes[index].second = uint32_t(nodes.size());
    build(first + left, count - left, depth + 1);
  }
};

}  // namespace

ElementHierarchy::ElementHierarchy(const std::vector<glm::dvec3>& positions,
                                   const std::vector<uint32_t>& indices, const std::vector<glm::dvec3>& normals)
    : vertexCount_(positions.size()) {
  const size_t elements = indices.size() / 3;
  RAD_CHECK(elements > 0 && elements < std::numeric_limits<uint32_t>::max());
  order_.resize(elements);
  std::iota(order_.begin(), order_.end(), 0u);
  Builder builder{positions, indices, nodes_, order_, {}};
  builder.centroids.resize(elements);
  for (size_t e = 0; e < elements; ++e)
    builder.centroids[e] =
        (positions[indices[3 * e]] + positions[indices[3 * e + 1]] + positions[indices[3 * e + 2]]) / 3.0;
  nodes_.reserve(4 * elements / kLeafSize + 1);
  builder.build(0, uint32_t(elements), 0);
  copyLeaves(positions, indices, normals);
}

void ElementHierarchy::copyLeaves(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& indices,
                                  const std::vector<glm::dvec3>& normals) {
  corners_.resize(order_.size());
  normals_.resize(order_.size());
  std::vector<uint32_t> vertices;  // the current leaf's, by first use
  for (Node& node : nodes_) {
    if (!node.leaf()) continue;
    node.vertexFirst = uint32_t(leafPositions_.size());
    vertices.clear();
    for (uint32_t i = node.first; i < node.first + node.count; ++i) {
      const uint32_t e = order_[i];
      for (size_t k = 0; k < 3; ++k) {
        const uint32_t v = indices[3 * size_t(e) + k];
        auto at = std::find(vertices.begin(), vertices.end(), v);
        if (at == vertices.end()) at = vertices.insert(at, v);
        corners_[i][k] = uint8_t(at - vertices.begin());
      }
      normals_[i] = normals[e];
    }
    for (uint32_t v : vertices) leafPositions_.push_back(positions[v]);
    node.vertexCount = uint32_t(vertices.size());
  }
}

}  // namespace rad
