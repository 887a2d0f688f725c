// The fixed-function lighting state of the OSMesa passes (display/viewer/osmesa_render.cpp): the
// scene's lights, light model and fog for the local model, the specular-only lighting of the
// hybrid model, and the materials of both.
#include "display/viewer/osmesa_lighting.h"

#include <GL/osmesa.h>

#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

namespace rad::viewer::detail {
namespace {

/// A colour or point of the scene as the four floats OpenGL takes.
std::array<GLfloat, 4> floats4(const glm::dvec4& v) {
  return {GLfloat(v.x), GLfloat(v.y), GLfloat(v.z), GLfloat(v.w)};
}

/// Sets vector parameter `name` of OpenGL light `light`.
void setVec4(GLenum light, GLenum name, const glm::dvec4& v) { glLightfv(light, name, floats4(v).data()); }

/// glLightModel: the scene's ambient light, local viewer and two-sided lighting.
void setupLightModel(const LightModel& lm) {
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, floats4(lm.ambient).data());
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, lm.localViewer ? GL_TRUE : GL_FALSE);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, lm.twoSided ? GL_TRUE : GL_FALSE);
}

/// The light's colours: ambient, diffuse and specular.
void setupLightColours(GLenum id, const Light& l) {
  setVec4(id, GL_AMBIENT, l.ambient);
  setVec4(id, GL_DIFFUSE, l.diffuse);
  setVec4(id, GL_SPECULAR, l.specular);
}

/// The light's position: its direction with w = 0 for a directional light, else its point.
void setupLightPosition(GLenum id, const Light& l) {
  if (l.type == Light::Type::Directional) setVec4(id, GL_POSITION, glm::dvec4(l.direction, 0.0));
  else setVec4(id, GL_POSITION, glm::dvec4(l.position, 1.0));
}

/// The light's distance attenuation: constant, linear and quadratic factors.
void setupAttenuation(GLenum id, const Light& l) {
  glLightf(id, GL_CONSTANT_ATTENUATION, GLfloat(l.attenuation.x));
  glLightf(id, GL_LINEAR_ATTENUATION, GLfloat(l.attenuation.y));
  glLightf(id, GL_QUADRATIC_ATTENUATION, GLfloat(l.attenuation.z));
}

/// A spot's cone: direction, cutoff and exponent.
void setupSpot(GLenum id, const Light& l) {
  const GLfloat d[3] = {GLfloat(l.direction.x), GLfloat(l.direction.y), GLfloat(l.direction.z)};
  glLightfv(id, GL_SPOT_DIRECTION, d);
  glLightf(id, GL_SPOT_CUTOFF, GLfloat(l.cutoffDeg));
  glLightf(id, GL_SPOT_EXPONENT, GLfloat(l.exponent));
}

/// The spot cone: direction, cutoff and exponent for a spot, a cutoff of 180 degrees otherwise.
void setupSpotCone(GLenum id, const Light& l) {
  if (l.type == Light::Type::Spot) setupSpot(id, l);
  else glLightf(id, GL_SPOT_CUTOFF, 180.0f);
}

/// One light as OpenGL light `id`: colours, position (w = 0 for directional), attenuation, and
/// the spot cone (a cutoff of 180 degrees for the others).
void setupLight(GLenum id, const Light& l) {
  glEnable(id);
  setupLightColours(id, l);
  setupLightPosition(id, l);
  setupAttenuation(id, l);
  setupSpotCone(id, l);
}

/// Throws when the scene has more lights than this OpenGL supports.
void checkLightCount(size_t count) {
  GLint maxLights = 8;
  glGetIntegerv(GL_MAX_LIGHTS, &maxLights);
  if (int(count) > maxLights)
    throw std::runtime_error("OpenGL: the scene has " + std::to_string(count) +
                             " lights, this OpenGL supports " + std::to_string(maxLights));
}

/// The scene's light model and lights (GL_LIGHT0...), specified with the view matrix loaded:
/// OpenGL stores their positions and spot directions in eye coordinates, i.e. fixed in the world.
void setupLights(const Scene& scene) {
  setupLightModel(scene.lightModel);
  checkLightCount(scene.lights.size());
  for (size_t i = 0; i < scene.lights.size(); ++i) setupLight(GLenum(GL_LIGHT0 + i), scene.lights[i]);
}

/// OpenGL's fog mode for the scene's.
GLint fogMode(Fog::Mode mode) {
  return mode == Fog::Mode::Linear ? GL_LINEAR : mode == Fog::Mode::Exp ? GL_EXP : GL_EXP2;
}

/// The fog's parameters: mode, colour, start and end (linear), density (exp, exp2).
void setFogParameters(const Fog& f) {
  glFogi(GL_FOG_MODE, fogMode(f.mode));
  glFogfv(GL_FOG_COLOR, floats4(f.color).data());
  glFogf(GL_FOG_START, GLfloat(f.start));
  glFogf(GL_FOG_END, GLfloat(f.end));
  glFogf(GL_FOG_DENSITY, GLfloat(f.density));
}

/// The scene's fog, when it has one.
void setupFog(const std::optional<Fog>& fog) {
  if (!fog) return;
  glEnable(GL_FOG);
  setFogParameters(*fog);
  glHint(GL_FOG_HINT, GL_NICEST);
}

/// Zero ambient and diffuse materials, and the vertex colour as the emission: radiosity
/// gives the diffuse and ambient part.
void vertexColourAsEmission() {
  const GLfloat zero[4] = {0, 0, 0, 1};
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, zero);
  glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, zero);
  glColorMaterial(GL_FRONT_AND_BACK, GL_EMISSION);
  glEnable(GL_COLOR_MATERIAL);
}

/// Lighting for the hybrid model. Diffuse and ambient come from radiosity: the material's are
/// zero and the vertex colour is the emission; lighting adds only the specular term, summed
/// after as a separate colour.
void setupSpecularOnly() {
  glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SEPARATE_SPECULAR_COLOR);
  glEnable(GL_LIGHTING);
  glEnable(GL_NORMALIZE);
  vertexColourAsEmission();
}

}  // namespace

void setLocalMaterial(const LocalBatch& b) {
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, glm::value_ptr(b.ambient));
  glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, glm::value_ptr(b.diffuse));
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, glm::value_ptr(b.specular));
  glMaterialfv(GL_FRONT_AND_BACK, GL_EMISSION, glm::value_ptr(b.emission));
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, b.shininess);
}

void setSpecularMaterial(const LocalBatch& b) {
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, glm::value_ptr(b.specular));
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, b.shininess);
}

void enableLocalLighting(const Scene& scene) {
  setupLights(scene);
  glEnable(GL_LIGHTING);
  glEnable(GL_NORMALIZE);
  glDisable(GL_COLOR_MATERIAL);
  setupFog(scene.fog);
}

void enableSpecularLighting(const Scene& scene) {
  setupLights(scene);
  setupSpecularOnly();
}

}  // namespace rad::viewer::detail
