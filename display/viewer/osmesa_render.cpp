// The OpenGL backend of the viewer: fixed-function OpenGL through OSMesa (llvmpipe), exactly as
// an interactive program would draw the result: lighting off, glColor per vertex,
// glShadeModel(GL_SMOOTH) or GL_FLAT (the last vertex of a triangle gives its colour), depth
// test on, matrices loaded with glLoadMatrixf; and the local model (renderOsMesaLocal): the
// scene's lights, light model, materials and fog through fixed-function lighting. Only OpenGL
// 1.1 entry points are used, all exported by libOSMesa; link OSMesa only (libGL in the same
// binary silently breaks it). The lighting state of the local and hybrid models is in
// display/viewer/osmesa_lighting.cpp.
#include <GL/osmesa.h>

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "display/viewer/osmesa_lighting.h"
#include "display/viewer/viewer.h"

namespace rad::viewer::detail {
namespace {

/// Display colour of wireframe edges.
constexpr GLubyte kWireColour[3] = {kWireByte, kWireByte, kWireByte};

/// What a pass draws at: the picture's size, the shading, back-face culling and the camera.
struct Frame {
  int width = 0, height = 0;
  Shading shade = Shading::Smooth;
  bool cullBack = false;
  glm::mat4 projection{1.0f}, view{1.0f};
};

/// A picture size as the messages give it: "WxH".
std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

/// Pushes the filled triangles back a little so that the wireframe drawn over them passes
/// the depth test.
void pushFilledBack() {
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
}

/// Turns off what shades the fill: the depth offset, colour material, lighting and fog.
void stopFillShading() {
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_COLOR_MATERIAL);
  glDisable(GL_LIGHTING);
  glDisable(GL_FOG);
}

/// Lines in the wire colour alone (no per-vertex colours or normals), passing the depth test
/// on the fill they were drawn from.
void wireLineState() {
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_COLOR_ARRAY);
  glColor3ubv(kWireColour);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glDepthFunc(GL_LEQUAL);
}

/// Draws the element edges of the `count` vertices' triangles over the picture in the wire
/// colour: no offset, lighting, fog, or per-vertex colours and normals.
void drawWireOverlay(GLsizei count) {
  stopFillShading();
  wireLineState();
  glDrawArrays(GL_TRIANGLES, 0, count);
}

/// Draws the fill (`drawFill`) of the `count` vertices and, when asked, the wireframe over it.
template <class DrawFill>
void drawUnderWireframe(bool wireframe, GLsizei count, DrawFill drawFill) {
  if (wireframe) pushFilledBack();
  drawFill();
  if (wireframe) drawWireOverlay(count);
}

struct ContextDeleter {
  void operator()(osmesa_context* c) const { OSMesaDestroyContext(c); }
};
using Context = std::unique_ptr<osmesa_context, ContextDeleter>;

/// The largest viewport of the current context: width and height.
std::array<GLint, 2> maxViewport() {
  std::array<GLint, 2> max = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max.data());
  return max;
}

/// Throws when a `width` x `height` picture exceeds the current context's largest viewport.
void checkViewportFits(int width, int height) {
  const std::array<GLint, 2> max = maxViewport();
  if (width > max[0] || height > max[1])
    throw std::runtime_error("OpenGL: a " + sizeText(width, height) + " picture exceeds the largest viewport, " +
                             sizeText(max[0], max[1]) + " (use a smaller size or --ssaa)");
}

/// An RGBA context with a 24-bit depth buffer.
Context createContext() {
  Context ctx(OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr));
  if (!ctx)
    throw std::runtime_error(
        "OpenGL: OSMesaCreateContextExt failed (is Mesa's OSMesa, libosmesa6, installed?)");
  return ctx;
}

/// Makes `ctx` current on `buffer`, a `width` x `height` picture of `type`.
void bindContext(osmesa_context* ctx, int width, int height, GLenum type, void* buffer) {
  if (!OSMesaMakeCurrent(ctx, buffer, type, width, height))
    throw std::runtime_error("OpenGL: OSMesaMakeCurrent failed for a " + sizeText(width, height) + " buffer");
}

/// Throws unless the context just made current answers and fits a `width` x `height` picture.
void checkCurrentContext(int width, int height) {
  if (!glGetString(GL_RENDERER))
    throw std::runtime_error(
        "OpenGL: glGetString(GL_RENDERER) returned null after OSMesaMakeCurrent (is libGL linked "
        "into the same binary? link OSMesa only)");
  checkViewportFits(width, height);
}

/// Creates an RGBA context with a 24-bit depth buffer and makes it current on `buffer` (RGBA,
/// `type` GL_UNSIGNED_BYTE or GL_FLOAT, bottom row first).
Context makeCurrent(int width, int height, GLenum type, void* buffer) {
  Context ctx = createContext();
  bindContext(ctx.get(), width, height, type, buffer);
  checkCurrentContext(width, height);
  return ctx;
}

/// Throws when OpenGL reports an error from the drawing.
void checkDrawError() {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw std::runtime_error("OpenGL: drawing failed with error 0x" + std::to_string(unsigned(error)));
}

/// Checks glGetError after drawing and releases the context.
void finish() {
  glFinish();
  checkDrawError();
  OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
}

/// Culls back faces, counter-clockwise fronts.
void cullBackFaces() {
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  glEnable(GL_CULL_FACE);  // also culls the GL_LINE pass of the wireframe
}

/// Culls back faces (counter-clockwise fronts) or none.
void setCulling(bool cullBack) {
  if (cullBack) cullBackFaces();
  else glDisable(GL_CULL_FACE);
}

/// Loads the camera: the projection and the view (modelview) matrices.
void loadCamera(const glm::mat4& projection, const glm::mat4& view) {
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixf(glm::value_ptr(projection));
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixf(glm::value_ptr(view));
}

/// Clears the whole `width` x `height` picture to black and far depth.
void clearFrame(int width, int height) {
  glViewport(0, 0, width, height);
  glClearColor(0, 0, 0, 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

/// No dithering, depth test LESS, flat or smooth shading.
void setRasterState(Shading shade) {
  glDisable(GL_DITHER);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glShadeModel(shade == Shading::Flat ? GL_FLAT : GL_SMOOTH);
}

/// The state every pass starts from: cleared black colour and far depth, depth test LESS, no
/// dithering, flat or smooth shading, culling of back faces or none, and the camera matrices.
void beginFrame(const Frame& f) {
  clearFrame(f.width, f.height);
  setCulling(f.cullBack);
  setRasterState(f.shade);
  loadCamera(f.projection, f.view);
}

/// Points the colour array at `colours`.
void bindColours(const std::vector<glm::vec4>& colours) {
  glEnableClientState(GL_COLOR_ARRAY);
  glColorPointer(4, GL_FLOAT, 0, colours.data());
}

/// Points the vertex and colour arrays at `positions` and `colours`, for unlit drawing.
void bindColouredVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec4>& colours) {
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, positions.data());
  bindColours(colours);
}

/// A fresh RGBA picture of T (`type` GL_UNSIGNED_BYTE or GL_FLOAT, bottom row first) drawn by
/// `draw` from the frame's start state, in a context of its own.
template <class T, class Draw>
std::vector<T> drawFrame(const Frame& f, GLenum type, Draw draw) {
  std::vector<T> buffer(size_t(f.width) * f.height * 4);
  Context ctx = makeCurrent(f.width, f.height, type, buffer.data());
  beginFrame(f);
  draw();
  return buffer;
}

/// Draws the list unlit in `colours`, the wireframe over it when asked, and finishes.
void drawUnlit(const DrawList& list, const std::vector<glm::vec4>& colours, bool wireframe) {
  glDisable(GL_LIGHTING);
  bindColouredVertices(list.positions, colours);
  const GLsizei count = GLsizei(list.positions.size());
  drawUnderWireframe(wireframe, count, [&] { glDrawArrays(GL_TRIANGLES, 0, count); });
  finish();
}

/// The list drawn unlit in `colours`: an RGBA picture of T (`type` GL_UNSIGNED_BYTE or GL_FLOAT,
/// bottom row first).
template <class T>
std::vector<T> unlitPass(const DrawList& list, const std::vector<glm::vec4>& colours, const Frame& f,
                         bool wireframe, GLenum type) {
  return drawFrame<T>(f, type, [&] { drawUnlit(list, colours, wireframe); });
}

/// Draws each batch's triangles with its material (`setMaterial`).
void drawEachBatch(const std::vector<LocalBatch>& batches, void (*setMaterial)(const LocalBatch&)) {
  for (const LocalBatch& b : batches) {
    setMaterial(b);
    glDrawArrays(GL_TRIANGLES, b.first, b.count);
  }
}

/// Draws each batch of the `vertexCount` vertices with its material (`setMaterial`), the
/// wireframe over them when asked, and finishes the frame.
void drawBatches(const std::vector<LocalBatch>& batches, size_t vertexCount, bool wireframe,
                 void (*setMaterial)(const LocalBatch&)) {
  drawUnderWireframe(wireframe, GLsizei(vertexCount), [&] { drawEachBatch(batches, setMaterial); });
  finish();
}

/// The radiance colours scaled by `scale` into [0, 1], where glColor values are clamped.
std::vector<glm::vec4> scaledColours(const std::vector<glm::vec4>& radiance, float scale) {
  std::vector<glm::vec4> scaled(radiance.size());
  for (size_t i = 0; i < scaled.size(); ++i)
    scaled[i] = glm::vec4(glm::min(glm::vec3(radiance[i]) * scale, glm::vec3(1.0f)), 1.0f);
  return scaled;
}

/// Points the vertex and normal arrays at `positions` and `normals`, for lit drawing.
void bindLitVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals) {
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, positions.data());
  glNormalPointer(GL_FLOAT, 0, normals.data());
}

/// The largest channel of the radiance colours (0 when all are black).
float peakChannel(const std::vector<glm::vec4>& radiance) {
  float peak = 0;
  for (const auto& c : radiance) peak = std::max({peak, c.r, c.g, c.b});
  return peak;
}

/// The RGB part of an RGBA picture, each value passed through `convert`.
template <class Out, class In, class Convert>
std::vector<Out> rgbOfRgba(const std::vector<In>& rgba, Convert convert) {
  std::vector<Out> rgb(rgba.size() / 4 * 3);
  for (size_t p = 0; p < rgba.size() / 4; ++p)
    for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = convert(rgba[p * 4 + c]);
  return rgb;
}

/// The RGB part of an RGBA picture.
std::vector<uint8_t> rgbOf(const std::vector<GLubyte>& rgba) {
  return rgbOfRgba<uint8_t>(rgba, [](GLubyte v) { return v; });
}

/// The radiance picture of the list (RGB floats, bottom row first) through a float colour
/// buffer. glColor values are clamped to [0, 1] on the way in, so the colours are scaled into
/// that range and the read-back scaled back.
std::vector<float> radiancePass(const DrawList& list, const Frame& f) {
  const float peak = peakChannel(list.radiance);
  const float scale = peak > 0 ? 1.0f / peak : 1.0f;
  const std::vector<GLfloat> buffer =
      unlitPass<GLfloat>(list, scaledColours(list.radiance, scale), f, /*wireframe=*/false, GL_FLOAT);
  return rgbOfRgba<float>(buffer, [&](GLfloat v) { return v / scale; });
}

/// The local model's frame: lit by the scene, each batch in its material.
void drawLocal(const LocalDrawList& list, const Scene& scene, bool wireframe) {
  enableLocalLighting(scene);
  bindLitVertices(list.positions, list.normals);
  drawBatches(list.batches, list.positions.size(), wireframe, setLocalMaterial);
}

/// The hybrid model's frame: the display colours as emission plus the scene's specular light.
void drawHybrid(const HybridDrawList& list, const Scene& scene, bool wireframe) {
  enableSpecularLighting(scene);
  bindLitVertices(list.positions, list.normals);
  bindColours(list.colours);
  drawBatches(list.batches, list.positions.size(), wireframe, setSpecularMaterial);
}

}  // namespace

void renderOsMesaLocal(const LocalDrawList& list, const Scene& scene, const glm::mat4& projection,
                       const glm::mat4& view, int width, int height, Shading shade, bool wireframe,
                       std::vector<uint8_t>& rgb) {
  const Frame f{width, height, shade, /*cullBack=*/false, projection, view};
  rgb = rgbOf(drawFrame<GLubyte>(f, GL_UNSIGNED_BYTE, [&] { drawLocal(list, scene, wireframe); }));
}

void renderOsMesaHybrid(const HybridDrawList& list, const Scene& scene, const glm::mat4& projection,
                        const glm::mat4& view, int width, int height, Shading shade,
                        bool wireframe, std::vector<uint8_t>& rgb) {
  const Frame f{width, height, shade, /*cullBack=*/false, projection, view};
  rgb = rgbOf(drawFrame<GLubyte>(f, GL_UNSIGNED_BYTE, [&] { drawHybrid(list, scene, wireframe); }));
}

void renderOsMesa(const DrawList& list, const glm::mat4& projection, const glm::mat4& view, int width,
                  int height, Shading shade, bool wireframe, std::vector<uint8_t>& rgb,
                  std::vector<float>* radiance, bool cullBack) {
  const Frame f{width, height, shade, cullBack, projection, view};
  rgb = rgbOf(unlitPass<GLubyte>(list, list.display, f, wireframe, GL_UNSIGNED_BYTE));
  if (radiance) *radiance = radiancePass(list, f);
}

}  // namespace rad::viewer::detail
