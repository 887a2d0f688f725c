#include "radiosity/formfactors/hemicube_depth_pyramid.h"

#include <algorithm>

namespace rad {

void DepthPyramid::build(const float* depth, int width, int height) {
  levels_.assign(1, Level{width, height, depth});
  for (size_t k = 1; width > 1 || height > 1; ++k) {
    const Level fine = levels_.back();
    width = (width + 1) / 2, height = (height + 1) / 2;
    if (data_.size() < k) data_.emplace_back();
    std::vector<float>& least = data_[k - 1];
    least.resize(size_t(width) * size_t(height));
    // Each block's least over its (up to) four blocks of the finer level.
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const int x1 = std::min(2 * x + 1, fine.width - 1), y1 = std::min(2 * y + 1, fine.height - 1);
        const float* row0 = fine.least + size_t(2 * y) * size_t(fine.width);
        const float* row1 = fine.least + size_t(y1) * size_t(fine.width);
        least[size_t(y) * size_t(width) + size_t(x)] =
            std::min(std::min(row0[2 * x], row0[x1]), std::min(row1[2 * x], row1[x1]));
      }
    levels_.push_back(Level{width, height, least.data()});
  }
}

bool DepthPyramid::covers(const PixelRect& rect, float depth) const {
  // Start at the finest level where the rectangle spans at most two blocks each way.
  int level = 0;
  while ((rect.x1 >> level) - (rect.x0 >> level) > 1 || (rect.y1 >> level) - (rect.y0 >> level) > 1)
    ++level;
  for (int y = rect.y0 >> level; y <= rect.y1 >> level; ++y)
    for (int x = rect.x0 >> level; x <= rect.x1 >> level; ++x)
      if (!blockCovers(level, x, y, rect, depth)) return false;
  return true;
}

bool DepthPyramid::blockCovers(int level, int x, int y, const PixelRect& rect, float depth) const {
  const Level& l = levels_[size_t(level)];
  if (l.least[size_t(y) * size_t(l.width) + size_t(x)] > depth) return true;
  if (level == 0) return false;
  // The finer blocks of this one inside the rectangle.
  const int k = level - 1;
  const Level& fine = levels_[size_t(k)];
  const int fx0 = std::max(2 * x, rect.x0 >> k), fx1 = std::min({2 * x + 1, rect.x1 >> k, fine.width - 1});
  const int fy0 = std::max(2 * y, rect.y0 >> k), fy1 = std::min({2 * y + 1, rect.y1 >> k, fine.height - 1});
  for (int fy = fy0; fy <= fy1; ++fy)
    for (int fx = fx0; fx <= fx1; ++fx)
      if (!blockCovers(k, fx, fy, rect, depth)) return false;
  return true;
}

}  // namespace rad
