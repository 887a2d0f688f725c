#pragma once
// Colour conversions, one home each: luminance, the sRGB transfer curve, display bytes.
#include <cstdint>

#include <glm/vec3.hpp>

namespace rad {

/// Luminance of linear sRGB / Rec. 709 primaries.
inline double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

/// The sRGB encoding of a linear value in [0, 1] (IEC 61966-2-1); values outside are clamped.
double srgbEncode(double linear);

/// The linear value of an sRGB-encoded value in [0, 1] (IEC 61966-2-1), the inverse of srgbEncode.
double srgbDecode(double encoded);

/// The display byte of linear radiosity B at exposure K: round(255 · sRGB(clamp(K·B))).
uint8_t displayByte(double radiosity, double exposure);

}  // namespace rad
