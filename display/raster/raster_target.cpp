// The render target's buffers: allocation and clears.
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "display/raster/raster.h"
#include "display/raster/raster_internal.h"

namespace raster {
namespace {

/// Fills n 32-bit words (vectorised by hand: -O2 does not vectorise std::fill of a float).
void fill32(uint32_t* p, size_t n, uint32_t value) {
  size_t i = 0;
#if RASTER_SSE2
  const __m128i v = _mm_set1_epi32(int(value));
  for (; i + 16 <= n; i += 16) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i + 4), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i + 8), v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i + 12), v);
  }
#endif
  for (; i < n; ++i) p[i] = value;
}

}  // namespace

Target::Target(int w, int h, bool withItem, bool withColor) {
  if (withItem) item.resize(1);
  if (withColor) color.resize(1);
  resize(w, h);
}

void Target::resize(int w, int h) {
  if (w < 1 || h < 1 || w > kMaxSize || h > kMaxSize)
    throw std::invalid_argument("raster::Target: size must be within 1..kMaxSize");
  width = w;
  height = h;
  const size_t n = size_t(w) * size_t(h);
  depth.assign(n, 1.0f);
  if (!item.empty()) item.assign(n, kNoItem);
  if (!color.empty()) color.assign(n, glm::vec4(0.0f));
  if (!hits.empty()) hits.assign(n, 0u);
}

void Target::clearDepth(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  fill32(reinterpret_cast<uint32_t*>(depth.data()), depth.size(), bits);
}

void Target::clearItem(uint32_t value) { fill32(item.data(), item.size(), value); }

void Target::clearColor(const glm::vec4& value) { std::fill(color.begin(), color.end(), value); }

void Target::clear() {
  clearDepth();
  clearItem();
  clearColor();
  std::fill(hits.begin(), hits.end(), 0u);
}

}  // namespace raster
