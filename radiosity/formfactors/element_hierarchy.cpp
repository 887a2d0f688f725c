#include "radiosity/formfactors/element_hierarchy.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "mesh/base/error.h"

namespace rad {
namespace {

/// The hierarchy over the triangles with corners positions[indices[3e..3e+2]]: each one's box
/// round its corners, split at their centroids.
BoxTree elementTree(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& indices) {
  const size_t elements = indices.size() / 3;
  std::vector<AlignedBox> boxes(elements);
  std::vector<glm::dvec3> centroids(elements);
  for (size_t e = 0; e < elements; ++e) {
    for (size_t k = 0; k < 3; ++k) boxes[e].add(positions[indices[3 * e + k]]);
    centroids[e] = (positions[indices[3 * e]] + positions[indices[3 * e + 1]] + positions[indices[3 * e + 2]]) / 3.0;
  }
  return buildBoxTree(boxes, centroids, ElementHierarchy::kLeafSize, BoxSplit::surfaceArea);
}

}  // namespace

ElementHierarchy::ElementHierarchy(const std::vector<glm::dvec3>& positions,
                                   const std::vector<uint32_t>& indices, const std::vector<glm::dvec3>& normals)
    : vertexCount_(positions.size()) {
  const size_t elements = indices.size() / 3;
  RAD_CHECK(elements > 0 && elements < std::numeric_limits<uint32_t>::max());
  BoxTree tree = elementTree(positions, indices);
  order_ = std::move(tree.order);
  nodes_.reserve(tree.nodes.size());
  for (const BoxTree::Node& node : tree.nodes) nodes_.push_back(Node{node});
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
