// Image files: PNG (display colours) and Radiance HDR (linear radiance) through stb, written
// atomically; PNG read back for the golden-image tests.
#include <functional>
#include <ostream>

#include <stb_image.h>
#include <stb_image_write.h>

#include "display/viewer/viewer.h"
#include "mesh/base/error.h"
#include "mesh/base/output_file.h"

namespace rad::viewer {
namespace {

/// stb's write callback: appends the bytes to the std::ostream `context`.
void toStream(void* context, void* data, int size) {
  static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}

/// Writes `path` atomically with an stb encoder (`encode` returns stb's result, 0 on failure);
/// `what` names the format in the error.
void writeWithStb(const std::string& path, const std::function<int(std::ostream&)>& encode,
                  const char* what) {
  writeFileAtomically(path, [&](std::ostream& out) {
    if (!encode(out)) throw inputError(path, std::string("a ") + what + " image encoded", "an encoder failure");
  });
}

/// A w x h image of stb's RGB bytes, which it frees.
Image imageFromStb(stbi_uc* data, int w, int h) {
  Image image;
  image.width = w;
  image.height = h;
  image.rgb.assign(data, data + size_t(w) * h * 3);
  stbi_image_free(data);
  return image;
}

/// stb's reason for its last failure, or "an unreadable file" when it gives none.
std::string stbFailure() {
  const char* why = stbi_failure_reason();
  return why ? why : "an unreadable file";
}

}  // namespace

void writePng(const std::string& path, const Image& image) {
  writeWithStb(path, [&](std::ostream& out) {
    return stbi_write_png_to_func(toStream, &out, image.width, image.height, 3, image.rgb.data(),
                                  image.width * 3);
  }, "PNG");
}

Image readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  if (!data) throw inputError(path, "a readable PNG image", stbFailure());
  return imageFromStb(data, w, h);
}

void writeHdr(const std::string& path, const Image& image) {
  if (image.radiance.size() != size_t(image.width) * image.height * 3)
    throw InternalError("writeHdr: the image has no radiance");
  writeWithStb(path, [&](std::ostream& out) {
    return stbi_write_hdr_to_func(toStream, &out, image.width, image.height, 3, image.radiance.data());
  }, "Radiance HDR");
}

}  // namespace rad::viewer
