// The display-only sections of the scene file: camera, and OpenGL's light model, lights and
// fog for the viewer's local model.
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

#include "mesh/scene/readers/scene_sections.h"

namespace rad::scene_file {
namespace {

/// GL_MAX_LIGHTS in every OpenGL implementation.
constexpr size_t kMaxLights = 8;

/// The value that the node's string names in `values`; `expected` lists the names for messages.
template <class T>
T namedValue(const Node& n, const std::map<std::string, T>& values, const char* expected) {
  const auto it = values.find(n.string());
  if (it == values.end()) n.fail(expected);
  return it->second;
}

/// The light's type, from its "type" key (node t).
Light::Type lightType(const Node& t) {
  static const std::map<std::string, Light::Type> types = {
      {"directional", Light::Type::Directional}, {"point", Light::Type::Point}, {"spot", Light::Type::Spot}};
  return namedValue(t, types, "\"directional\", \"point\" or \"spot\"");
}

/// The keys a light of that type accepts.
std::vector<std::string> lightKeys(Light::Type type) {
  std::vector<std::string> keys = {"type", "ambient", "diffuse", "specular"};
  if (type == Light::Type::Directional) keys.push_back("direction");
  else keys.insert(keys.end(), {"position", "attenuation"});
  if (type == Light::Type::Spot) keys.insert(keys.end(), {"direction", "cutoff_deg", "exponent"});
  return keys;
}

/// The key a light of its type must have.
Node required(const Node& n, const char* key) {
  if (!n.has(key))
    n.failWith(std::string("a \"") + key + "\" key for a " + n["type"].string() + " light", "none");
  return n[key];
}

/// A light's direction (node d): non-zero.
glm::dvec3 readDirection(const Node& d) {
  const glm::dvec3 direction = d.vec3();
  if (glm::length(direction) == 0) d.fail("a non-zero direction");
  return direction;
}

/// The light's position and direction, as its type needs them.
void readPlacement(const Node& n, Light& l) {
  if (l.type != Light::Type::Point) l.direction = readDirection(required(n, "direction"));
  if (l.type != Light::Type::Directional) l.position = required(n, "position").vec3();
}

/// Attenuation coefficients kc, kl, kq: >= 0, not all zero.
glm::dvec3 readAttenuation(const Node& a) {
  const glm::dvec3 k = nonNegativeRgb(a, "an attenuation coefficient >= 0");
  if (k == glm::dvec3(0.0)) a.fail("at least one non-zero coefficient");
  return k;
}

/// A spot light's cone: its cutoff angle and exponent.
void readSpotCone(const Node& n, Light& l) {
  l.cutoffDeg = required(n, "cutoff_deg").number(0, 90, "[0, 90]");
  if (n.has("exponent")) l.exponent = n["exponent"].number(0, 128, "[0, 128]");
}

/// The light's colours, attenuation and spot cone.
void readShining(const Node& n, Light& l) {
  if (n.has("ambient")) l.ambient = n["ambient"].color();
  if (n.has("diffuse")) l.diffuse = n["diffuse"].color();
  if (n.has("specular")) l.specular = n["specular"].color();
  if (n.has("attenuation")) l.attenuation = readAttenuation(n["attenuation"]);
  if (l.type == Light::Type::Spot) readSpotCone(n, l);
}

/// A light is an object with a "type" key.
void checkLightObject(const Node& n) {
  if (!n.value().is_object()) n.fail("an object");
  if (!n.has("type")) n.failWith("a \"type\" key", "none");
}

/// One light: its type, then the keys that type accepts.
Light readLight(const Node& n) {
  checkLightObject(n);
  Light l;
  l.type = lightType(n["type"]);
  n.expectObject(lightKeys(l.type));
  readPlacement(n, l);
  readShining(n, l);
  return l;
}

/// Fog's "mode".
Fog::Mode fogMode(const Node& n) {
  static const std::map<std::string, Fog::Mode> modes = {
      {"linear", Fog::Mode::Linear}, {"exp", Fog::Mode::Exp}, {"exp2", Fog::Mode::Exp2}};
  return namedValue(n, modes, "\"linear\", \"exp\" or \"exp2\"");
}

/// The camera (node n) looks somewhere, with an up vector across its view.
void checkView(const Node& n, const Camera& c) {
  glm::dvec3 view = c.target - c.eye;
  if (glm::length(view) == 0) n["target"].failWith("a target away from the eye", "the eye");
  if (glm::length(glm::cross(view, c.up)) <= 1e-9 * glm::length(view) * glm::length(c.up))
    n["up"].failWith("an up vector not parallel to the view direction", "a parallel one");
}

/// The camera's "eye", "target" and "up" keys are there.
void checkCameraKeys(const Node& n) {
  for (const char* key : {"eye", "target", "up"})
    if (!n.has(key)) n.failWith(std::string("a \"") + key + "\" key", "none");
}

/// The fog's colour, linear range (start, end) and density, where given.
void readFogShape(const Node& n, Fog& f) {
  if (n.has("color")) f.color = n["color"].color();
  if (n.has("start")) f.start = n["start"].number();
  if (n.has("end")) f.end = n["end"].number();
  if (n.has("density")) f.density = n["density"].number(0, HUGE_VAL, "[0, inf)");
}

/// Linear fog (node n) has a depth range: end != start.
void checkFogRange(const Node& n, const Fog& f) {
  if (f.mode == Fog::Mode::Linear && f.end == f.start)
    n.failWith("linear fog with end != start", "end = start = " + std::to_string(f.end));
}

}  // namespace

Camera readCamera(const Node& n) {
  n.expectObject({"eye", "target", "up", "fov_y_deg"});
  Camera c;
  checkCameraKeys(n);
  c.eye = n["eye"].vec3();
  c.target = n["target"].vec3();
  c.up = n["up"].vec3();
  if (n.has("fov_y_deg")) c.fovYDeg = n["fov_y_deg"].number(1e-3, 179.999, "(0, 180)");
  checkView(n, c);
  return c;
}

void readLightModel(const Node& n, LightModel& model) {
  n.expectObject({"ambient", "local_viewer", "two_sided"});
  if (n.has("ambient")) model.ambient = n["ambient"].color();
  if (n.has("local_viewer")) model.localViewer = n["local_viewer"].boolean();
  if (n.has("two_sided")) model.twoSided = n["two_sided"].boolean();
}

void readLights(const Node& n, std::vector<Light>& lights) {
  n.expectArray(0, "lights");
  if (n.size() > kMaxLights) n.fail("at most 8 lights (OpenGL's GL_MAX_LIGHTS)");
  for (size_t i = 0; i < n.size(); ++i) lights.push_back(readLight(n[i]));
}

Fog readFog(const Node& n) {
  n.expectObject({"mode", "color", "start", "end", "density"});
  Fog f;
  if (!n.has("mode")) n.failWith("a \"mode\" key", "none");
  f.mode = fogMode(n["mode"]);
  readFogShape(n, f);
  checkFogRange(n, f);
  return f;
}

}  // namespace rad::scene_file
