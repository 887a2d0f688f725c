#pragma once
// Internal to the contact lines (contact_lines.cpp): the planar pieces' bounding boxes, and the
// grid that finds which pieces' boxes may meet, so that only those are tested for contacts.
#include <cmath>
#include <unordered_map>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

#include "mesh/base/spatial_hash.h"
#include "mesh/planar_pieces.h"

namespace rad::meshing {

/// An axis-aligned box.
struct Box {
  glm::dvec3 lo{HUGE_VAL}, hi{-HUGE_VAL};
};

/// Whether the boxes overlap.
inline bool boxesMeet(const Box& a, const Box& b) {
  return !glm::any(glm::lessThan(b.hi, a.lo)) && !glm::any(glm::lessThan(a.hi, b.lo));
}

/// Each piece's bounding box, grown by `pad`.
std::vector<Box> paddedBoxes(const PointTable& table, const std::vector<Piece>& pieces, double pad);

/// The pieces' boxes in a hash over the scene's box cut into cells × cells × cells cells
/// (each axis divided alike, so cells are boxes, not cubes): the hash works in those grid
/// coordinates. Candidates come cell by cell in x, y, z order (then the large pieces), which
/// orders the contact lines and so decides which new point is made first.
///
/// Two cells per axis per cube root of the pieces, or as many as make a cell the size of a
/// typical piece if that is more (a finely tessellated model, 300 000 triangles a few
/// centimetres across, filed thousands of its faces per cell, and each visited them all),
/// at most kMaxCells. A piece that would be filed in more than kMaxCellsPerPiece cells (a
/// room's floor in a fine grid) is large: large pieces go in a coarse grid of world cubes
/// (2∛n a side, at most kMaxCoarseCells), which every piece visits too, and a large piece's
/// candidates among the others are found once, from their side.
class PieceBoxes {
 public:
  static constexpr double kMaxCells = 1024;
  static constexpr double kMaxCellsPerPiece = 512;
  static constexpr double kMaxCoarseCells = 64;

  /// Files the boxes (kept by reference: they must outlive this).
  explicit PieceBoxes(const std::vector<Box>& boxes);

  /// Calls f(s) for the pieces s whose boxes may meet piece p's (s may come more than once):
  /// those filed in a cell p's box touches, and the large ones near it.
  template <class F>
  void visit(size_t p, F&& f) const {
    if (large_[p]) {
      auto it = smallOfLarge_.find(int(p));
      if (it != smallOfLarge_.end())
        for (int s : it->second) f(s);
    } else {
      hash_.visit(grid(boxes_[p].lo), grid(boxes_[p].hi), f);
    }
    coarse_.visit(boxes_[p].lo, boxes_[p].hi, f);
  }

 private:
  /// x in grid coordinates, clamped to the grid.
  glm::dvec3 grid(const glm::dvec3& x) const {
    return glm::clamp((x - lo_) / cell_, 0.0, double(cells_ - 1));
  }

  const std::vector<Box>& boxes_;
  int cells_ = 1;
  glm::dvec3 lo_{0.0}, cell_{1.0};
  SpatialHash hash_{1.0}, coarse_{1.0};
  std::vector<bool> large_;
  std::unordered_map<int, std::vector<int>> smallOfLarge_;
};

}  // namespace rad::meshing
