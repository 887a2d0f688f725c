#pragma once
// A bounding-volume hierarchy over a hemicube's elements (mesh/base/box_tree.h), built once
// per geometry and shared by every hemicube that draws it: a cube skips whole subtrees below
// its base plane or hidden behind what it has already drawn, without touching their elements.
// Each leaf keeps its own copy of its corners and normals, so that a cube reads a leaf from
// one place.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/base/box_tree.h"

namespace rad {

class ElementHierarchy {
 public:
  /// A subtree (BoxTree::Node: the box [lo, hi] around its elements' corners and its
  /// elements, which are order()[first, first + count); a leaf has second == 0, an inner
  /// node's first child is the node after it and its second child is nodes()[second]). A
  /// leaf's corners' distinct vertices are leafPositions()[vertexFirst, vertexFirst +
  /// vertexCount).
  struct Node : BoxTree::Node {
    uint32_t vertexFirst = 0, vertexCount = 0;
  };

  /// At most this many elements in a leaf, so at most 3 × kLeafSize vertices.
  static constexpr uint32_t kLeafSize = 8;

  /// The hierarchy of the triangles with corners positions[indices[3e..3e+2]] and unit
  /// normal normals[e] (element e), split by the surface area heuristic over binned
  /// centroids (BoxSplit::surfaceArea). At least one element.
  ElementHierarchy(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& indices,
                   const std::vector<glm::dvec3>& normals);

  const std::vector<Node>& nodes() const { return nodes_; }
  /// The elements, each subtree's contiguous.
  const std::vector<uint32_t>& order() const { return order_; }
  /// Per element of order(): its corners as indices into its leaf's vertices, and its normal.
  const std::vector<std::array<uint8_t, 3>>& corners() const { return corners_; }
  const std::vector<glm::dvec3>& normals() const { return normals_; }
  /// The leaves' vertices (copies of the positions), leaf after leaf.
  const std::vector<glm::dvec3>& leafPositions() const { return leafPositions_; }
  /// The vertex and element counts it was built for.
  size_t vertexCount() const { return vertexCount_; }
  size_t elementCount() const { return order_.size(); }

 private:
  /// Gives each leaf its vertices, and each of its elements its corners among them.
  void copyLeaves(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& indices,
                  const std::vector<glm::dvec3>& normals);

  std::vector<Node> nodes_;
  std::vector<uint32_t> order_;
  std::vector<std::array<uint8_t, 3>> corners_;
  std::vector<glm::dvec3> normals_, leafPositions_;
  size_t vertexCount_;
};

}  // namespace rad
