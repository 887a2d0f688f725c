// Mesa's software OpenGL (OSMesa, llvmpipe) drawing the same item buffers as the raster core,
// for benchmarks that compare the two. Link OSMesa only (never libGL/GLU/GLUT in the same
// binary). Rendering goes into an off-screen framebuffer object with an RGBA8 colour buffer
// (the item id, byte for byte) and a 32-bit FLOAT depth buffer, like raster::Target.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace bench {

/// A minimal OSMesa context rendering item buffers of clip-space triangles (benchmarks only).
/// Not thread-safe; the context is made current on the calling thread by each call.
class OsMesaItemBuffer {
 public:
  /// Creates a context for targets up to maxWidth x maxHeight; throws std::runtime_error with a clear message if OSMesa or the renderer string is unavailable.
  OsMesaItemBuffer(int maxWidth, int maxHeight);
  ~OsMesaItemBuffer();
  OsMesaItemBuffer(const OsMesaItemBuffer&) = delete;
  OsMesaItemBuffer& operator=(const OsMesaItemBuffer&) = delete;

  /// The GL_RENDERER string (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
  std::string renderer() const;

  /// Draws the triangles into a width x height viewport with reversed depth exactly as our core's hemicube does: glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), glDepthFunc(GL_GREATER), clear depth 0, clear ids to 0xFFFFFFFF; per-triangle id written as a flat RGBA8 colour (id packed into r,g,b,a bytes). Reads the ids back into `items` (width*height, row 0 = bottom, like glReadPixels).
  /// As raster::drawTriangles: indices null = non-indexed, ids null = triangle number; an index
  /// >= vertexCount throws std::out_of_range, a size outside 1..max std::invalid_argument.
  void draw(int width, int height, const glm::vec4* clip, size_t vertexCount,
            const uint32_t* indices, size_t triangleCount, const uint32_t* ids,
            std::vector<uint32_t>& items);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bench
