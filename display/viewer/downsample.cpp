// Supersampling's last step: pictures drawn k times larger per axis, box-filtered down in
// linear light and flipped to top row first, as image files store them.
#include <algorithm>
#include <array>
#include <cmath>

#include "display/viewer/viewer_internal.h"
#include "mesh/base/color.h"

namespace rad::viewer::internal {
namespace {

/// The linear value whose srgbEncode is `want`, by bisection on it (so the curve has one home).
double srgbDecode(double want) {
  double lo = 0, hi = 1;
  for (int i = 0; i < 60; ++i) {
    double mid = 0.5 * (lo + hi);
    (srgbEncode(mid) < want ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// srgbDecode of every display byte.
std::array<double, 256> makeSrgbDecodeTable() {
  std::array<double, 256> t{};
  for (int b = 0; b < 256; ++b) t[b] = srgbDecode(b / 255.0);
  return t;
}

/// Linear value of each sRGB display byte: the inverse of mesh/base/color.h's srgbEncode.
const std::array<double, 256>& srgbDecodeTable() {
  static const std::array<double, 256> table = makeSrgbDecodeTable();
  return table;
}

/// The sum in linear light of channel c over the k x k block of pixel (x, y) of a picture
/// `bigWidth` wide.
template <class T, class Decode>
double blockSum(const std::vector<T>& big, int bigWidth, int x, int y, int c, int k, Decode decode) {
  double sum = 0;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) sum += decode(big[(size_t(y * k + j) * bigWidth + x * k + i) * 3 + c]);
  return sum;
}

/// Box-filters a (width·k) × (height·k) bottom-up picture down to width × height, top row first:
/// each value is taken to linear light by `decode`, averaged, and brought back by `encode`.
template <class T, class Decode, class Encode>
std::vector<T> boxFilter(const std::vector<T>& big, int width, int height, int k, Decode decode,
                         Encode encode) {
  if (k == 1) return topRowFirst(big, width, height, 3);  // no round trip through linear light
  std::vector<T> out(size_t(width) * height * 3);
  const int bigWidth = width * k;
  const double norm = 1.0 / (k * k);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        out[(size_t(height - 1 - y) * width + x) * 3 + c] = encode(blockSum(big, bigWidth, x, y, c, k, decode) * norm);
  return out;
}

}  // namespace

uint8_t toByte(float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

std::vector<uint8_t> targetBytes(const raster::Target& target) { return targetRgb<uint8_t>(target, toByte); }

std::vector<uint8_t> downsampleBytes(const std::vector<uint8_t>& big, int width, int height, int k) {
  const auto& table = srgbDecodeTable();
  return boxFilter(big, width, height, k, [&](uint8_t v) { return table[v]; },
                   [](double x) { return uint8_t(std::lround(255 * srgbEncode(x))); });
}

std::vector<float> downsampleFloats(const std::vector<float>& big, int width, int height, int k) {
  return boxFilter(big, width, height, k, [](float v) { return double(v); },
                   [](double x) { return float(x); });
}

Image imageOf(const std::vector<uint8_t>& big, const RenderOptions& o) {
  Image image;
  image.width = o.width;
  image.height = o.height;
  image.rgb = downsampleBytes(big, o.width, o.height, o.ssaa);
  return image;
}

}  // namespace rad::viewer::internal
