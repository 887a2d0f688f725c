#include "mesh/scene/readers/texture_mean.h"

#include <array>
#include <climits>
#include <cmath>
#include <memory>

#include <stb_image.h>

#include "mesh/base/color.h"
#include "mesh/base/error.h"

namespace rad {
namespace {

/// The linear value of an 8-bit sRGB code (IEC 61966-2-1), for every code.
std::array<double, 256> srgbDecodeTable() {
  std::array<double, 256> table{};
  for (int code = 0; code < 256; ++code) table[size_t(code)] = srgbDecode(code / 255.0);
  return table;
}

/// "one stb_image cannot <verb> (<its reason>)".
std::string stbFailure(const std::string& verb) {
  return "one stb_image cannot " + verb + " (" + stbi_failure_reason() + ")";
}

/// The image is one stb_image reads, of at most kMaxTexturePixels.
void checkImageSize(const unsigned char* bytes, int size, const std::string& where) {
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(bytes, size, &w, &h, &channels))
    throw inputError(where, "a PNG or JPEG image", stbFailure("read"));
  if (double(w) * double(h) > kMaxTexturePixels)
    throw inputError(where, "an image of at most 2^26 pixels", std::to_string(w) + " x " + std::to_string(h));
}

/// An image decoded by stb_image to 8-bit RGB, which frees it.
struct Rgb8 {
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels{nullptr, stbi_image_free};
  int w = 0, h = 0;
};

/// The image decoded to 8-bit RGB.
Rgb8 decodeRgb(const unsigned char* bytes, int size, const std::string& where) {
  Rgb8 image;
  int channels = 0;
  image.pixels.reset(stbi_load_from_memory(bytes, size, &image.w, &image.h, &channels, 3));
  if (!image.pixels) throw inputError(where, "a PNG or JPEG image", stbFailure("decode"));
  return image;
}

}  // namespace

glm::dvec3 meanLinearColour(const unsigned char* bytes, size_t size, const std::string& where) {
  if (size == 0 || size > size_t(INT_MAX))
    throw inputError(where, "an image of 1 byte to 2 GiB", std::to_string(size) + " bytes");
  checkImageSize(bytes, int(size), where);
  const Rgb8 image = decodeRgb(bytes, int(size), where);
  static const std::array<double, 256> linear = srgbDecodeTable();
  glm::dvec3 sum(0.0);
  const size_t pixels = size_t(image.w) * size_t(image.h);
  for (size_t i = 0; i < 3 * pixels; ++i) sum[int(i % 3)] += linear[image.pixels.get()[i]];
  return sum / double(pixels);
}

}  // namespace rad
