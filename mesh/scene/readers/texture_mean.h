#pragma once
// The mean colour of an image file (PNG, JPEG, ... as stb_image decodes them): what a diffuse
// solver takes for a texture it cannot map, the reflectance of a textured material.
#include <string>

#include <glm/vec3.hpp>

namespace rad {

/// An image larger than this (pixels) is refused before it is decoded.
constexpr double kMaxTexturePixels = double(1 << 26);

/// The linear mean colour of an 8-bit sRGB-encoded image (`size` bytes of an encoded file at
/// `bytes`), each pixel decoded to linear before averaging; alpha is ignored. Throws InputError
/// naming `where` when the bytes are not an image stb_image decodes or it is too large.
glm::dvec3 meanLinearColour(const unsigned char* bytes, size_t size, const std::string& where);

}  // namespace rad
