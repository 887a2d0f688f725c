#pragma once
// A uniform grid of cubic cells stored sparsely by cell: the one spatial index for "what is
// near this point or box" across the parts (points to snap to, elements near a patch, vertices
// inside an edge).
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

namespace rad {

class SpatialHash {
 public:
  using Cell = std::array<int64_t, 3>;

  /// Cells of edge `cellSize` (> 0), the grid anchored at `origin`.
  explicit SpatialHash(double cellSize, const glm::dvec3& origin = glm::dvec3(0.0))
      : origin_(origin), cell_(cellSize) {}

  Cell cellOf(const glm::dvec3& p) const {
    const glm::dvec3 q = (p - origin_) / cell_;
    return {int64_t(std::floor(q.x)), int64_t(std::floor(q.y)), int64_t(std::floor(q.z))};
  }

  /// Files `id` under the cell holding p.
  void insert(const glm::dvec3& p, int id) { cells_[cellOf(p)].push_back(id); }

  /// Files `id` under every cell the box [lo, hi] touches.
  void insert(const glm::dvec3& lo, const glm::dvec3& hi, int id) {
    forCells(lo, hi, [&](const Cell& c) { cells_[c].push_back(id); });
  }

  /// Calls f(id) for every id filed under a cell the box [lo, hi] touches, cell by cell in
  /// x, y, z order and in insertion order within a cell: an id filed under several of those
  /// cells comes once per cell.
  template <class F>
  void visit(const glm::dvec3& lo, const glm::dvec3& hi, F&& f) const {
    forCells(lo, hi, [&](const Cell& c) {
      auto it = cells_.find(c);
      if (it != cells_.end())
        for (int id : it->second) f(id);
    });
  }

  double cellSize() const { return cell_; }

 private:
  template <class F>
  void forCells(const glm::dvec3& lo, const glm::dvec3& hi, F&& f) const {
    const Cell a = cellOf(lo), b = cellOf(hi);
    for (int64_t x = a[0]; x <= b[0]; ++x)
      for (int64_t y = a[1]; y <= b[1]; ++y)
        for (int64_t z = a[2]; z <= b[2]; ++z) f(Cell{x, y, z});
  }

  struct CellHash {
    size_t operator()(const Cell& c) const {
      return size_t(uint64_t(c[0]) * 73856093u ^ uint64_t(c[1]) * 19349663u ^ uint64_t(c[2]) * 83492791u);
    }
  };

  glm::dvec3 origin_;
  double cell_;
  std::unordered_map<Cell, std::vector<int>, CellHash> cells_;
};

}  // namespace rad
