// The OpenGL backend of the viewer: fixed-function OpenGL through OSMesa (llvmpipe), exactly as
// an interactive program would draw the result: lighting off, glColor per vertex,
// glShadeModel(GL_SMOOTH) or GL_FLAT (the last vertex of a triangle gives its colour), depth
// test on, matrices loaded with glLoadMatrixf; and the local model (renderOsMesaLocal): the
// scene's lights, light model, materials and fog through fixed-function lighting. Only OpenGL
// 1.1 entry points are used, all exported by libOSMesa; link OSMesa only (libGL in the same
// binary silently breaks it).
#include <GL/osmesa.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "display/viewer.h"

namespace rad::viewer::detail {
namespace {

/// Display colour of wireframe edges.
constexpr GLubyte kWireColour[3] = {kWireByte, kWireByte, kWireByte};

/// Pushes the filled triangles back a little so that the wireframe drawn over them passes
/// the depth test.
void pushFilledBack() {
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
}

/// Draws the element edges of the `count` vertices' triangles over the picture in the wire
/// colour: no offset, lighting, fog, or per-vertex colours and normals.
void drawWireOverlay(GLsizei count) {
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_COLOR_MATERIAL);
  glDisable(GL_LIGHTING);
  glDisable(GL_FOG);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_COLOR_ARRAY);
  glColor3ubv(kWireColour);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glDepthFunc(GL_LEQUAL);
  glDrawArrays(GL_TRIANGLES, 0, count);
}

struct ContextDeleter {
  void operator()(osmesa_context* c) const { OSMesaDestroyContext(c); }
};
using Context = std::unique_ptr<osmesa_context, ContextDeleter>;

/// Throws when a `width` x `height` picture exceeds the current context's largest viewport.
void checkViewportFits(int width, int height) {
  GLint maxViewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
  if (width > maxViewport[0] || height > maxViewport[1])
    throw std::runtime_error("OpenGL: a " + std::to_string(width) + "x" + std::to_string(height) +
                             " picture exceeds the largest viewport, " + std::to_string(maxViewport[0]) +
                             "x" + std::to_string(maxViewport[1]) + " (use a smaller size or --ssaa)");
}

/// Draws the list into `buffer` (RGBA, `type` GL_UNSIGNED_BYTE or GL_FLOAT, bottom row first).
/// Creates an RGBA context with a 24-bit depth buffer and makes it current on `buffer`.
Context makeCurrent(int width, int height, GLenum type, void* buffer) {
  Context ctx(OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr));
  if (!ctx)
    throw std::runtime_error(
        "OpenGL: OSMesaCreateContextExt failed (is Mesa's OSMesa, libosmesa6, installed?)");
  if (!OSMesaMakeCurrent(ctx.get(), buffer, type, width, height))
    throw std::runtime_error("OpenGL: OSMesaMakeCurrent failed for a " + std::to_string(width) + "x" +
                             std::to_string(height) + " buffer");
  if (!glGetString(GL_RENDERER))
    throw std::runtime_error(
        "OpenGL: glGetString(GL_RENDERER) returned null after OSMesaMakeCurrent (is libGL linked "
        "into the same binary? link OSMesa only)");
  checkViewportFits(width, height);
  return ctx;
}

/// Checks glGetError after drawing and releases the context.
void finish() {
  glFinish();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw std::runtime_error("OpenGL: drawing failed with error 0x" + std::to_string(unsigned(error)));
  OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
}

/// Culls back faces (counter-clockwise fronts) or none.
void setCulling(bool cullBack) {
  if (cullBack) {
    glFrontFace(GL_CCW);
    glCullFace(GL_BACK);
    glEnable(GL_CULL_FACE);  // also culls the GL_LINE pass of the wireframe
  } else {
    glDisable(GL_CULL_FACE);
  }
}

/// Loads the camera: the projection and the view (modelview) matrices.
void loadCamera(const glm::mat4& projection, const glm::mat4& view) {
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixf(glm::value_ptr(projection));
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixf(glm::value_ptr(view));
}

/// The state every pass starts from: cleared black colour and far depth, depth test LESS, no
/// dithering, flat or smooth shading, culling of back faces or none, and the camera matrices.
void beginFrame(int width, int height, Shading shade, bool cullBack, const glm::mat4& projection,
                const glm::mat4& view) {
  glViewport(0, 0, width, height);
  glClearColor(0, 0, 0, 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  setCulling(cullBack);
  glDisable(GL_DITHER);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glShadeModel(shade == Shading::Flat ? GL_FLAT : GL_SMOOTH);
  loadCamera(projection, view);
}

void drawPass(const DrawList& list, const std::vector<glm::vec4>& colours, const glm::mat4& projection,
              const glm::mat4& view, int width, int height, Shading shade, bool wireframe,
              GLenum type, void* buffer, bool cullBack) {
  Context ctx = makeCurrent(width, height, type, buffer);
  beginFrame(width, height, shade, cullBack, projection, view);
  glDisable(GL_LIGHTING);

  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, list.positions.data());
  glColorPointer(4, GL_FLOAT, 0, colours.data());
  const GLsizei count = GLsizei(list.positions.size());
  if (wireframe) pushFilledBack();
  glDrawArrays(GL_TRIANGLES, 0, count);
  if (wireframe) drawWireOverlay(count);
  finish();
}

void setVec4(GLenum light, GLenum name, const glm::dvec4& v) {
  const GLfloat f[4] = {GLfloat(v.x), GLfloat(v.y), GLfloat(v.z), GLfloat(v.w)};
  glLightfv(light, name, f);
}

/// glLightModel: the scene's ambient light, local viewer and two-sided lighting.
void setupLightModel(const LightModel& lm) {
  const GLfloat ambient[4] = {GLfloat(lm.ambient.x), GLfloat(lm.ambient.y), GLfloat(lm.ambient.z),
                              GLfloat(lm.ambient.w)};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, lm.localViewer ? GL_TRUE : GL_FALSE);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, lm.twoSided ? GL_TRUE : GL_FALSE);
}

/// The light's distance attenuation: constant, linear and quadratic factors.
void setupAttenuation(GLenum id, const Light& l) {
  glLightf(id, GL_CONSTANT_ATTENUATION, GLfloat(l.attenuation.x));
  glLightf(id, GL_LINEAR_ATTENUATION, GLfloat(l.attenuation.y));
  glLightf(id, GL_QUADRATIC_ATTENUATION, GLfloat(l.attenuation.z));
}

/// The spot cone: direction, cutoff and exponent for a spot, a cutoff of 180 degrees otherwise.
void setupSpotCone(GLenum id, const Light& l) {
  if (l.type == Light::Type::Spot) {
    const GLfloat d[3] = {GLfloat(l.direction.x), GLfloat(l.direction.y), GLfloat(l.direction.z)};
    glLightfv(id, GL_SPOT_DIRECTION, d);
    glLightf(id, GL_SPOT_CUTOFF, GLfloat(l.cutoffDeg));
    glLightf(id, GL_SPOT_EXPONENT, GLfloat(l.exponent));
  } else {
    glLightf(id, GL_SPOT_CUTOFF, 180.0f);
  }
}

/// One light as OpenGL light `id`: colours, position (w = 0 for directional), attenuation, and
/// the spot cone (a cutoff of 180 degrees for the others).
void setupLight(GLenum id, const Light& l) {
  glEnable(id);
  setVec4(id, GL_AMBIENT, l.ambient);
  setVec4(id, GL_DIFFUSE, l.diffuse);
  setVec4(id, GL_SPECULAR, l.specular);
  if (l.type == Light::Type::Directional)
    setVec4(id, GL_POSITION, glm::dvec4(l.direction, 0.0));
  else
    setVec4(id, GL_POSITION, glm::dvec4(l.position, 1.0));
  setupAttenuation(id, l);
  setupSpotCone(id, l);
}

/// The scene's light model and lights (GL_LIGHT0...), specified with the view matrix loaded:
/// OpenGL stores their positions and spot directions in eye coordinates, i.e. fixed in the world.
void setupLights(const Scene& scene) {
  setupLightModel(scene.lightModel);
  GLint maxLights = 8;
  glGetIntegerv(GL_MAX_LIGHTS, &maxLights);
  if (int(scene.lights.size()) > maxLights)
    throw std::runtime_error("OpenGL: the scene has " + std::to_string(scene.lights.size()) +
                             " lights, this OpenGL supports " + std::to_string(maxLights));
  for (size_t i = 0; i < scene.lights.size(); ++i) setupLight(GLenum(GL_LIGHT0 + i), scene.lights[i]);
}

/// OpenGL's fog mode for the scene's.
GLint fogMode(Fog::Mode mode) {
  return mode == Fog::Mode::Linear ? GL_LINEAR : mode == Fog::Mode::Exp ? GL_EXP : GL_EXP2;
}

/// The scene's fog, when it has one.
void setupFog(const std::optional<Fog>& fog) {
  if (!fog) return;
  const Fog& f = *fog;
  glEnable(GL_FOG);
  glFogi(GL_FOG_MODE, fogMode(f.mode));
  const GLfloat c[4] = {GLfloat(f.color.x), GLfloat(f.color.y), GLfloat(f.color.z), GLfloat(f.color.w)};
  glFogfv(GL_FOG_COLOR, c);
  glFogf(GL_FOG_START, GLfloat(f.start));
  glFogf(GL_FOG_END, GLfloat(f.end));
  glFogf(GL_FOG_DENSITY, GLfloat(f.density));
  glHint(GL_FOG_HINT, GL_NICEST);
}

/// Every material of the local model: ambient, diffuse, specular, emission and shininess.
void setLocalMaterial(const LocalBatch& b) {
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, glm::value_ptr(b.ambient));
  glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, glm::value_ptr(b.diffuse));
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, glm::value_ptr(b.specular));
  glMaterialfv(GL_FRONT_AND_BACK, GL_EMISSION, glm::value_ptr(b.emission));
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, b.shininess);
}

/// The hybrid model's materials: specular colour and shininess only.
void setSpecularMaterial(const LocalBatch& b) {
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, glm::value_ptr(b.specular));
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, b.shininess);
}

/// Draws each batch of the `vertexCount` vertices with its material (`setMaterial`), the
/// wireframe over them when asked, and finishes the frame.
void drawBatches(const std::vector<LocalBatch>& batches, size_t vertexCount, bool wireframe,
                 void (*setMaterial)(const LocalBatch&)) {
  if (wireframe) pushFilledBack();
  for (const LocalBatch& b : batches) {
    setMaterial(b);
    glDrawArrays(GL_TRIANGLES, b.first, b.count);
  }
  if (wireframe) drawWireOverlay(GLsizei(vertexCount));
  finish();
}

/// Lighting for the hybrid model. Diffuse and ambient come from radiosity: the material's are
/// zero and the vertex colour is the emission; lighting adds only the specular term, summed
/// after as a separate colour.
void setupSpecularOnly() {
  glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SEPARATE_SPECULAR_COLOR);
  glEnable(GL_LIGHTING);
  glEnable(GL_NORMALIZE);
  const GLfloat zero[4] = {0, 0, 0, 1};
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, zero);
  glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, zero);
  glColorMaterial(GL_FRONT_AND_BACK, GL_EMISSION);
  glEnable(GL_COLOR_MATERIAL);
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

/// The RGB part of an RGBA picture.
std::vector<uint8_t> rgbOf(const std::vector<GLubyte>& rgba) {
  std::vector<uint8_t> rgb(rgba.size() / 4 * 3);
  for (size_t p = 0; p < rgba.size() / 4; ++p)
    for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = rgba[p * 4 + c];
  return rgb;
}

/// The local model's lighting: the scene's lights, normalised normals, material colours (not
/// vertex colours), and its fog.
void enableLocalLighting(const Scene& scene) {
  setupLights(scene);
  glEnable(GL_LIGHTING);
  glEnable(GL_NORMALIZE);
  glDisable(GL_COLOR_MATERIAL);
  setupFog(scene.fog);
}

/// The radiance picture of the list (RGB floats, bottom row first) through a float colour
/// buffer. glColor values are clamped to [0, 1] on the way in, so the colours are scaled into
/// that range and the read-back scaled back.
std::vector<float> radiancePass(const DrawList& list, const glm::mat4& projection, const glm::mat4& view,
                                int width, int height, Shading shade, bool cullBack) {
  const size_t pixels = size_t(width) * height;
  const float peak = peakChannel(list.radiance);
  const float scale = peak > 0 ? 1.0f / peak : 1.0f;
  std::vector<GLfloat> buffer(pixels * 4);
  drawPass(list, scaledColours(list.radiance, scale), projection, view, width, height, shade,
           /*wireframe=*/false, GL_FLOAT, buffer.data(), cullBack);
  std::vector<float> radiance(pixels * 3);
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) radiance[p * 3 + c] = buffer[p * 4 + c] / scale;
  return radiance;
}

}  // namespace

void renderOsMesaLocal(const LocalDrawList& list, const Scene& scene, const glm::mat4& projection,
                       const glm::mat4& view, int width, int height, Shading shade, bool wireframe,
                       std::vector<uint8_t>& rgb) {
  std::vector<GLubyte> buffer(size_t(width) * height * 4);
  Context ctx = makeCurrent(width, height, GL_UNSIGNED_BYTE, buffer.data());
  beginFrame(width, height, shade, /*cullBack=*/false, projection, view);
  enableLocalLighting(scene);
  bindLitVertices(list.positions, list.normals);
  drawBatches(list.batches, list.positions.size(), wireframe, setLocalMaterial);
  rgb = rgbOf(buffer);
}

void renderOsMesaHybrid(const HybridDrawList& list, const Scene& scene, const glm::mat4& projection,
                        const glm::mat4& view, int width, int height, Shading shade,
                        bool wireframe, std::vector<uint8_t>& rgb) {
  std::vector<GLubyte> buffer(size_t(width) * height * 4);
  Context ctx = makeCurrent(width, height, GL_UNSIGNED_BYTE, buffer.data());
  beginFrame(width, height, shade, /*cullBack=*/false, projection, view);
  setupLights(scene);
  setupSpecularOnly();

  bindLitVertices(list.positions, list.normals);
  glEnableClientState(GL_COLOR_ARRAY);
  glColorPointer(4, GL_FLOAT, 0, list.colours.data());
  drawBatches(list.batches, list.positions.size(), wireframe, setSpecularMaterial);
  rgb = rgbOf(buffer);
}

void renderOsMesa(const DrawList& list, const glm::mat4& projection, const glm::mat4& view, int width,
                  int height, Shading shade, bool wireframe, std::vector<uint8_t>& rgb,
                  std::vector<float>* radiance, bool cullBack) {
  const size_t pixels = size_t(width) * height;
  {
    std::vector<GLubyte> buffer(pixels * 4);
    drawPass(list, list.display, projection, view, width, height, shade, wireframe, GL_UNSIGNED_BYTE,
             buffer.data(), cullBack);
    rgb = rgbOf(buffer);
  }
  if (radiance) *radiance = radiancePass(list, projection, view, width, height, shade, cullBack);
}

}  // namespace rad::viewer::detail
