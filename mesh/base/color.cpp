#include "mesh/base/color.h"

#include <algorithm>
#include <cmath>

namespace rad {

double srgbEncode(double linear) {
  double x = std::clamp(linear, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}

double srgbDecode(double encoded) {
  double x = std::clamp(encoded, 0.0, 1.0);
  return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

uint8_t displayByte(double radiosity, double exposure) {
  return uint8_t(std::lround(255 * srgbEncode(exposure * radiosity)));
}

}  // namespace rad
