// The raster core: OpenGL's triangle pipeline in miniature, on the CPU, with no global state.
//
// Input is clip-space vertices (glm::vec4, OpenGL convention: visible iff -w <= x,y,z <= w).
// Triangles entirely outside one plane are rejected by outcodes before any other work; the
// others are clipped in homogeneous space against the near and far planes and a guard band
// (so window coordinates stay bounded), snapped to 1/2^kSubpixelBits pixel and rasterised
// with exact 64-bit edge functions and a top-left fill rule: the pixel centres of a closed
// mesh are hit exactly once, also along edges cut by the near plane.
//
// Window coordinates follow OpenGL: x_w = (x_ndc+1)/2*width, y_w = (y_ndc+1)/2*height,
// depth = (z_ndc+1)/2 (interpolated linearly in window space), pixel (i, j) has its centre at
// (i+0.5, j+0.5), and buffers are stored row by row with ROW 0 AT THE BOTTOM of the image
// (as glReadPixels returns them): index = j*width + i.
//
// Fill rule, stated in the y-up window: a pixel centre exactly on an edge belongs to the
// triangle iff the edge is a left edge (the triangle lies on its +x side) or a top edge
// (horizontal, the triangle lies below it). Front faces are counter-clockwise in the window.
//
// A Target must not be drawn into from several threads at once: besides the covered pixels,
// the item+depth path rewrites (with their own values) up to 3 pixels right of a triangle's
// bounding box, possibly outside the scissor rectangle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace raster {

/// Value of the item buffer where no triangle was drawn.
constexpr uint32_t kNoItem = 0xFFFFFFFFu;
/// Sub-pixel precision of snapped window coordinates (1/256 pixel).
constexpr int kSubpixelBits = 8;
/// Largest supported target width or height (keeps the fixed-point edge functions exact).
constexpr int kMaxSize = 16384;

/// Colour interpolation: none (colour not written), flat (the LAST vertex of the triangle, as
/// OpenGL's provoking vertex) or smooth (perspective-correct Gouraud).
enum class Shade { None, Flat, Smooth };
/// Face culling: none, or remove back faces (clockwise in window coordinates).
enum class Cull { None, Back };
/// Depth comparison: LESS (default, clear depth to 1) or GREATER (reversed depth, clear to 0).
enum class DepthFunc { Less, Greater };
/// Clip-space depth convention (glClipControl): OpenGL's -w <= z <= w with depth = (z/w+1)/2,
/// or 0 <= z <= w with depth = z/w. The latter with z = near and DepthFunc::Greater is
/// "reversed depth": depth = near/w keeps float's relative precision at every distance.
enum class ClipDepth { NegativeOneToOne, ZeroToOne };

/// Pixel rectangle [x, x+width) x [y, y+height), y counted from the bottom row.
struct Rect {
  int x = 0, y = 0, width = 0, height = 0;
};

/// Render target: equally sized buffers, row-major, row 0 = BOTTOM row, index = y*width + x.
struct Target {
  int width = 0, height = 0;
  std::vector<float> depth;      ///< 32-bit float depth in [0, 1], always present.
  std::vector<uint32_t> item;    ///< Item ids (kNoItem = empty); empty vector = not written.
  std::vector<glm::vec4> color;  ///< RGBA colour; empty vector = not written.
  /// Test hook: if sized width*height, counts every fragment written (uses the generic path).
  std::vector<uint32_t> hits;

  /// Internal per-vertex workspace reused between draws (no allocation once warm).
  struct Scratch {
    std::vector<glm::vec4> window;  // x_w, y_w, depth, 1/w
    std::vector<glm::ivec2> fixed;  // snapped x_w, y_w
    std::vector<uint16_t> code;     // outcodes
  } scratch;

  Target() = default;
  /// Allocates a width x height target (1..kMaxSize, else std::invalid_argument), cleared.
  Target(int width, int height, bool withItem = true, bool withColor = false);
  /// Reallocates the buffers that exist (depth, item, colour, hits) for a new size, cleared.
  void resize(int width, int height);
  /// Fills the depth buffer (default: the far plane, 1).
  void clearDepth(float value = 1.0f);
  /// Fills the item buffer (default: kNoItem).
  void clearItem(uint32_t value = kNoItem);
  /// Fills the colour buffer (default: transparent black).
  void clearColor(const glm::vec4& value = glm::vec4(0.0f));
  /// Clears depth to 1, items to kNoItem, colour to transparent black and hits to 0.
  void clear();
  /// Buffer index of pixel (x, y), y = 0 being the bottom row.
  size_t index(int x, int y) const { return static_cast<size_t>(y) * width + x; }
};

/// Fixed-function state of one draw call.
struct State {
  Cull cull = Cull::None;
  Shade shade = Shade::None;
  bool depthTest = true;     ///< Depth test on. When off, depth is neither tested nor written (GL).
  DepthFunc depthFunc = DepthFunc::Less;  ///< Comparison of the depth test (glDepthFunc).
  ClipDepth clipDepth = ClipDepth::NegativeOneToOne;  ///< Depth convention (glClipControl).
  bool depthWrite = true;    ///< Write the depth of fragments passing the test (glDepthMask).
  bool scissorTest = false;  ///< Restrict drawing to `scissor` (clamped to the target).
  Rect scissor;
};

/// Transforms positions by mvp into clip space: clip[i] = mvp * vec4(positions[i], 1).
void transform(const glm::mat4& mvp, const glm::vec3* positions, size_t count, glm::vec4* clip);
/// Same for a vector, resizing `clip` to positions.size().
void transform(const glm::mat4& mvp, const std::vector<glm::vec3>& positions,
               std::vector<glm::vec4>& clip);

/// Draws triangles given in clip space into `target`.
/// - indices: 3 vertex indices per triangle, all < vertexCount (else std::out_of_range);
///   null = non-indexed, triangle t uses vertices 3t..3t+2.
/// - ids: value written to the item buffer (if the target has one) per triangle; null = t.
/// - colors: per-vertex RGBA; colour is written iff state.shade != None, colors is non-null
///   and the target has a colour buffer.
/// Cost: O(vertexCount) vertex work per call plus the triangles'. The item+depth fast path
/// is taken when no colour is written, depth test and write are on, the target has an item
/// buffer and no hits hook; it gives exactly the generic path's result.
void drawTriangles(Target& target, const State& state, const glm::vec4* clip, size_t vertexCount,
                   const uint32_t* indices, size_t triangleCount, const uint32_t* ids = nullptr,
                   const glm::vec4* colors = nullptr);

/// Draws line segments given in clip space into `target`, in one constant colour.
/// - indices: 2 vertex indices per segment, all < vertexCount (else std::out_of_range); null =
///   non-indexed, segment s uses vertices 2s, 2s+1.
/// Pipeline: each segment is clipped in homogeneous space against the near and far planes (per
/// state.clipDepth), projected to window coordinates (as for triangles) and clipped to the
/// viewport [0, width] x [0, height] (Liang-Barsky). Rasterisation is a DDA on pixel centres
/// along the major axis (|dx| >= |dy|: x, else y): the pixels whose centre coordinate c on
/// that axis lies in [min, max) of the endpoints' (half-open, independent of the segment's
/// direction, so a shared edge drawn from either end gives the same pixels) get, on the minor
/// axis, the pixel containing the segment's point at c (floor). So a segment covers one pixel
/// per column (or row), like OpenGL's diamond-exit rule up to ties. Depth is interpolated
/// linearly in window space (as OpenGL does for lines) and moved TOWARD THE VIEWER by
/// `depthBias` (window depth units: subtracted for DepthFunc::Less, added for Greater, then
/// clamped to [0, 1]), so that edges drawn after their own faces pass the depth test.
/// Depth test/write and scissor follow `state`; cull and shade are ignored. The colour is
/// written when the target has a colour buffer; the item buffer is not touched; the hits hook
/// counts fragments written.
void drawLines(Target& target, const State& state, const glm::vec4* clip, size_t vertexCount,
               const uint32_t* indices, size_t lineCount, const glm::vec4& color,
               float depthBias = 0.0f);

}  // namespace raster
