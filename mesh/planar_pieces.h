#pragma once
// Internal to buildPatchMesh: the planar pieces that surfaces are meshed as, their points
// held once each in a shared table so that equal points compare by id.
#include <array>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/polygon_mesher.h"
#include "mesh/scene/geometry.h"
#include "mesh/scene/scene.h"

namespace rad::meshing {

/// Every distinct position gets one id, so equal points compare by id.
class PointTable {
 public:
  /// The id of p, made when p is new (-0 and 0 are one position).
  int id(const glm::dvec3& p) {
    Key k{p.x + 0.0, p.y + 0.0, p.z + 0.0};  // + 0.0 folds -0 into 0
    auto [it, added] = index_.emplace(k, int(points_.size()));
    if (added) points_.push_back(p);
    return it->second;
  }
  const glm::dvec3& operator[](int i) const { return points_[i]; }
  int size() const { return int(points_.size()); }

 private:
  using Key = std::array<double, 3>;
  struct Hash {
    size_t operator()(const Key& k) const {
      std::hash<double> h;
      return h(k[0]) * 73856093u ^ h(k[1]) * 19349663u ^ h(k[2]) * 83492791u;
    }
  };
  std::vector<glm::dvec3> points_;
  std::unordered_map<Key, int, Hash> index_;
};

/// A planar polygon with holes whose ring points are ids in a PointTable, and the contact
/// lines inside it that meshing keeps as element edges.
struct Piece {
  int surface = -1;
  PlaneFrame frame;
  std::vector<std::vector<int>> rings;
  std::vector<std::array<int, 2>> lines;
  bool meshFace = false;  ///< a face of a mesh file
};

/// The piece's rings in its own 2D frame, with their point ids (no lines).
Polygon2 projectedRings(const PointTable& table, const Piece& piece);

/// Splits every polygon of the scene into planar pieces, in surface order; a non-planar one is
/// triangulated, with a warning.
std::vector<Piece> planarPieces(const Scene& scene, PointTable& table,
                                std::vector<std::string>& warnings);

}  // namespace rad::meshing
