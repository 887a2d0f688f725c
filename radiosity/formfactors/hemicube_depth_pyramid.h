#pragma once
// A hierarchical depth test over one hemicube face: levels of the least depth of ever larger
// blocks of pixels, so that "is all of this rectangle already nearer than d?" reads a few
// values. Depth is reversed (near/distance, greater is nearer, cleared to 0): a subtree
// whose nearest possible depth is smaller than every pixel's under its rectangle cannot
// win any of them.
#include <vector>

namespace rad {

/// An inclusive rectangle of pixels [x0, x1] × [y0, y1], row 0 at the bottom.
struct PixelRect {
  int x0, y0, x1, y1;
};

class DepthPyramid {
 public:
  /// Rebuilds the levels over `depth` (width × height, row by row from the bottom), which
  /// must stay in place while the pyramid is queried.
  void build(const float* depth, int width, int height);
  /// Whether every pixel of `rect` (inside the face) holds a depth greater than `depth`.
  bool covers(const PixelRect& rect, float depth) const;

 private:
  struct Level {
    int width = 0, height = 0;
    const float* least = nullptr;  // per block, row by row
  };
  /// Whether every pixel of block (x, y) of level `level` that lies in `rect` holds a depth
  /// greater than `depth`, looking into finer levels where the block's least one does not.
  bool blockCovers(int level, int x, int y, const PixelRect& rect, float depth) const;

  std::vector<Level> levels_;           // level 0 the pixels, level k blocks of 2^k × 2^k
  std::vector<std::vector<float>> data_;  // the storage of levels 1, 2, ...
};

}  // namespace rad
