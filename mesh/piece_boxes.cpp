// Planar pieces ▸ contact lines: which pieces may touch, their bounding boxes filed in a grid.
#include "mesh/piece_boxes.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "mesh/scene/geometry.h"

namespace rad::meshing {
namespace {

/// The box around the boxes.
Box enclosing(const std::vector<Box>& boxes) {
  Box all;
  for (const Box& b : boxes) all.lo = glm::min(all.lo, b.lo), all.hi = glm::max(all.hi, b.hi);
  return all;
}

/// The median of the boxes' largest sides.
double medianSide(const std::vector<Box>& boxes) {
  std::vector<double> sides;
  for (const Box& b : boxes) {
    const glm::dvec3 d = b.hi - b.lo;
    sides.push_back(std::max({d.x, d.y, d.z}));
  }
  return median(std::move(sides));
}

}  // namespace

std::vector<Box> paddedBoxes(const PointTable& table, const std::vector<Piece>& pieces, double pad) {
  std::vector<Box> boxes(pieces.size());
  for (size_t p = 0; p < pieces.size(); ++p)
    for (const auto& ring : pieces[p].rings)
      for (int id : ring) {
        boxes[p].lo = glm::min(boxes[p].lo, table[id] - pad);
        boxes[p].hi = glm::max(boxes[p].hi, table[id] + pad);
      }
  return boxes;
}

PieceBoxes::PieceBoxes(const std::vector<Box>& boxes) : boxes_(boxes) {
  const Box scene = enclosing(boxes);
  const glm::dvec3 extent = scene.hi - scene.lo;
  const double widest = std::max({extent.x, extent.y, extent.z, 1e-300});
  const double perRoot = 2 * std::cbrt(double(boxes.size()));
  cells_ = int(std::clamp(std::max(perRoot, widest / medianSide(boxes)), 1.0, kMaxCells));
  lo_ = scene.lo;
  cell_ = glm::max(extent / double(cells_), glm::dvec3(1e-300));
  coarse_ = SpatialHash(widest / std::clamp(perRoot, 1.0, kMaxCoarseCells), scene.lo);
  large_.assign(boxes.size(), false);
  for (size_t p = 0; p < boxes.size(); ++p) {
    const glm::dvec3 n = glm::floor(grid(boxes[p].hi)) - glm::floor(grid(boxes[p].lo)) + 1.0;
    large_[p] = n.x * n.y * n.z > kMaxCellsPerPiece;
    if (large_[p])
      coarse_.insert(boxes[p].lo, boxes[p].hi, int(p));
    else
      hash_.insert(grid(boxes[p].lo), grid(boxes[p].hi), int(p));
  }
  // Each large piece's candidates among the small ones, each once, in piece order.
  std::vector<int> last(boxes.size(), -1);
  for (size_t s = 0; s < boxes.size(); ++s) {
    if (large_[s]) continue;
    coarse_.visit(boxes[s].lo, boxes[s].hi, [&](int r) {
      if (last[size_t(r)] == int(s) || !boxesMeet(boxes[s], boxes[size_t(r)])) return;
      last[size_t(r)] = int(s);
      smallOfLarge_[r].push_back(int(s));
    });
  }
}

}  // namespace rad::meshing
