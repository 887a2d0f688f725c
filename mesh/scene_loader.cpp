// Reads and validates the version-1 scene file of DESIGN.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "mesh/error.h"
#include "mesh/input_file.h"
#include "mesh/geometry.h"
#include "mesh/material_presets.h"
#include "mesh/mesh_file.h"
#include "mesh/scene.h"

namespace rad {
namespace {

using json = nlohmann::ordered_json;

/// Says what a JSON value is, for "found ..." in messages.
std::string describe(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return j.get<bool>() ? "true" : "false";
    case json::value_t::string: return "the string " + j.dump();
    case json::value_t::array: return "an array of " + std::to_string(j.size()) + " items";
    case json::value_t::object: return "an object";
    default: return "the number " + j.dump();
  }
}

/// "line L, column C" of the first occurrence of `token` in `text`.
std::string lineColumn(const std::string& text, const std::string& token) {
  size_t at = token.empty() ? std::string::npos : text.find(token);
  if (at == std::string::npos) return "somewhere";
  size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  size_t lineStart = text.rfind('\n', at);
  size_t column = at - (lineStart == std::string::npos ? 0 : lineStart + 1) + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out;
}

/// A JSON value with its location ("scene.json: surfaces[3].polygon") for messages.
class Node {
 public:
  Node(const json& j, std::string file, std::string path)
      : j_(j), file_(std::move(file)), path_(std::move(path)) {}

  const json& value() const { return j_; }
  std::string where() const { return path_.empty() ? file_ : file_ + ": " + path_; }
  [[noreturn]] void fail(const std::string& expected) const {
    throw inputError(where(), expected, describe(j_));
  }
  [[noreturn]] void failWith(const std::string& expected, const std::string& found) const {
    throw inputError(where(), expected, found);
  }

  bool has(const char* key) const { return j_.contains(key); }
  Node operator[](const char* key) const {
    return Node(j_.at(key), file_, path_.empty() ? key : path_ + "." + key);
  }
  Node operator[](size_t i) const {
    return Node(j_.at(i), file_, path_ + "[" + std::to_string(i) + "]");
  }
  size_t size() const { return j_.size(); }

  /// Requires an object whose keys are all among `accepted`.
  void expectObject(const std::vector<std::string>& accepted) const {
    if (!j_.is_object()) fail("an object");
    for (const auto& item : j_.items()) {
      if (std::find(accepted.begin(), accepted.end(), item.key()) == accepted.end())
        throw inputError(where(), "one of the keys " + join(accepted),
                         "the unknown key \"" + item.key() + "\"");
    }
  }
  void expectArray(size_t minSize, const std::string& what) const {
    if (!j_.is_array()) fail("an array of " + what);
    if (j_.size() < minSize)
      fail("at least " + std::to_string(minSize) + " " + what);
  }
  double number() const {
    if (!j_.is_number()) fail("a number");
    double x = j_.get<double>();
    if (!std::isfinite(x)) fail("a finite number");
    return x;
  }
  double number(double lo, double hi, const std::string& range) const {
    double x = number();
    if (!(x >= lo && x <= hi)) fail("a number in " + range);
    return x;
  }
  std::string string() const {
    if (!j_.is_string()) fail("a string");
    return j_.get<std::string>();
  }
  bool boolean() const {
    if (!j_.is_boolean()) fail("true or false");
    return j_.get<bool>();
  }
  glm::dvec3 vec3() const {
    if (!j_.is_array() || j_.size() != 3) fail("an array of 3 numbers");
    return {(*this)[size_t(0)].number(), (*this)[1].number(), (*this)[2].number()};
  }
  /// An RGB colour; OpenGL's RGBA also accepted, alpha 1 by default.
  glm::dvec4 color() const {
    if (!j_.is_array() || (j_.size() != 3 && j_.size() != 4)) fail("an array of 3 or 4 numbers");
    glm::dvec4 c(1.0);
    for (size_t i = 0; i < j_.size(); ++i) c[int(i)] = (*this)[i].number();
    return c;
  }

 private:
  const json& j_;
  std::string file_, path_;
};

glm::dvec3 nonNegativeRgb(const Node& n, const std::string& what) {
  glm::dvec3 c = n.vec3();
  for (int i = 0; i < 3; ++i)
    if (c[i] < 0) n[size_t(i)].fail(what);
  return c;
}

glm::dvec3 reflectanceRgb(const Node& n) {
  glm::dvec3 c = n.vec3();
  for (int i = 0; i < 3; ++i)
    if (!(c[i] >= 0 && c[i] < 1)) n[size_t(i)].fail("a reflectance in [0, 1)");
  return c;
}

Material readMaterial(const Node& n, const std::string& name) {
  n.expectObject({"reflectance", "emission", "preset", "ambient", "diffuse", "specular",
                  "shininess"});
  Material m;
  m.name = name;
  bool haveLocal = false;
  if (n.has("preset")) {
    Node p = n["preset"];
    const MaterialPreset* preset = findMaterialPreset(p.string());
    if (!preset) p.fail("one of " + join(materialPresetNames()));
    m.preset = preset->name;
    m.ambient = preset->ambient;
    m.diffuse = preset->diffuse;
    m.specular = preset->specular;
    m.shininess = preset->shininess;
    m.reflectance = glm::dvec3(preset->diffuse);
    haveLocal = true;
  }
  if (n.has("diffuse")) {
    m.diffuse = n["diffuse"].color();
    m.reflectance = glm::dvec3(m.diffuse);
  }
  if (n.has("ambient")) m.ambient = n["ambient"].color();
  if (n.has("specular")) m.specular = n["specular"].color();
  if (n.has("shininess")) m.shininess = n["shininess"].number(0, 128, "[0, 128]");
  if (n.has("reflectance")) {
    m.reflectance = reflectanceRgb(n["reflectance"]);
  } else if (!n.has("preset") && !n.has("diffuse")) {
    n.failWith("\"reflectance\", \"diffuse\" or \"preset\"", "none of them");
  }
  for (int i = 0; i < 3; ++i)
    if (!(m.reflectance[i] >= 0 && m.reflectance[i] < 1))
      n.failWith("a diffuse colour usable as reflectance, in [0, 1)",
                 std::to_string(m.reflectance[i]));
  if (!haveLocal) {
    // Without a preset the local model sees the radiosity colour, as a user would expect.
    if (!n.has("diffuse")) m.diffuse = glm::dvec4(m.reflectance, 1.0);
    if (!n.has("ambient")) m.ambient = glm::dvec4(m.reflectance, 1.0);
  }
  if (n.has("emission")) m.emission = nonNegativeRgb(n["emission"], "a finite emission >= 0");
  return m;
}

Ring readRing(const Node& n, const std::string& what) {
  n.expectArray(3, what);
  Ring ring;
  for (size_t i = 0; i < n.size(); ++i) ring.push_back(n[i].vec3());
  return ring;
}

/// The transform of a mesh file: scale, then rotations about x, y, z, then translation.
glm::dmat4 readTransform(const Node& n) {
  n.expectObject({"scale", "rotate_deg", "translate"});
  glm::dvec3 scale(1.0), rotate(0.0), translate(0.0);
  if (n.has("scale")) {
    Node s = n["scale"];
    scale = s.value().is_array() ? s.vec3() : glm::dvec3(s.number());
    for (int i = 0; i < 3; ++i)
      if (scale[i] == 0) s.fail("a non-zero scale");
  }
  if (n.has("rotate_deg")) rotate = n["rotate_deg"].vec3();
  if (n.has("translate")) translate = n["translate"].vec3();
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate);
  m = glm::rotate(m, glm::radians(rotate.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotate.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotate.x), glm::dvec3(1, 0, 0));
  return glm::scale(m, scale);
}

class SceneReader {
 public:
  SceneReader(Scene& scene, std::string file, std::string baseDir)
      : scene_(scene), file_(std::move(file)), baseDir_(std::move(baseDir)) {}

  void read(const json& root) {
    Node n(root, file_, "");
    n.expectObject({"version", "units", "materials", "surfaces", "camera", "light_model",
                    "lights", "fog", "solver"});
    if (!n.has("version")) n.failWith("a \"version\" key", "none");
    if (n["version"].value() != 1) n["version"].fail("version 1");
    if (n.has("units")) scene_.units = n["units"].string();
    if (!n.has("materials")) n.failWith("a \"materials\" object", "none");
    readMaterials(n["materials"]);
    if (!n.has("surfaces")) n.failWith("a \"surfaces\" array", "none");
    readSurfaces(n["surfaces"]);
    if (n.has("camera")) scene_.camera = readCamera(n["camera"]);
    if (n.has("light_model")) readLightModel(n["light_model"]);
    if (n.has("lights")) readLights(n["lights"]);
    if (n.has("fog")) scene_.fog = readFog(n["fog"]);
    if (n.has("solver")) readSolver(n["solver"]);
  }

 private:
  void readMaterials(const Node& n) {
    if (!n.value().is_object()) n.fail("an object of named materials");
    for (const auto& item : n.value().items())
      scene_.materials.push_back(readMaterial(n[item.key().c_str()], item.key()));
  }

  int materialIndex(const Node& n) const {
    std::string name = n.string();
    for (size_t i = 0; i < scene_.materials.size(); ++i)
      if (scene_.materials[i].name == name) return int(i);
    std::vector<std::string> names;
    for (const auto& m : scene_.materials) names.push_back(m.name);
    n.fail("a material defined in \"materials\" (" + join(names) + ")");
  }

  void readSurfaces(const Node& n) {
    n.expectArray(1, "surfaces");
    std::set<std::string> names;
    for (size_t i = 0; i < n.size(); ++i) {
      Node s = n[i];
      s.expectObject({"name", "material", "polygon", "holes", "two_sided", "mesh", "transform"});
      std::string name = s.has("name") ? s["name"].string() : "surface" + std::to_string(i);
      if (!names.insert(name).second) s["name"].fail("a name no other surface has");
      bool twoSided = s.has("two_sided") && s["two_sided"].boolean();
      if (s.has("polygon") == s.has("mesh"))
        s.failWith("exactly one of \"polygon\" and \"mesh\"",
                   s.has("polygon") ? "both" : "neither");
      if (s.has("polygon"))
        readPolygonSurface(s, name, twoSided);
      else
        readMeshSurface(s, name, twoSided);
    }
  }

  void readPolygonSurface(const Node& s, const std::string& name, bool twoSided) {
    if (s.has("transform")) s["transform"].failWith("no transform on a polygon surface",
                                                     "a transform");
    if (!s.has("material")) s.failWith("a \"material\" key", "none");
    Surface surface;
    surface.name = name;
    surface.where = s.where();
    surface.twoSided = twoSided;
    surface.material = materialIndex(s["material"]);
    Polygon polygon;
    polygon.outer = readRing(s["polygon"], "vertices [x, y, z]");
    if (s.has("holes")) {
      Node holes = s["holes"];
      holes.expectArray(0, "holes");
      for (size_t h = 0; h < holes.size(); ++h)
        polygon.holes.push_back(readRing(holes[h], "vertices [x, y, z]"));
    }
    validatePolygon(polygon, s);
    surface.polygons.push_back(std::move(polygon));
    scene_.surfaces.push_back(std::move(surface));
  }

  void readMeshSurface(const Node& s, const std::string& name, bool twoSided) {
    if (s.has("holes")) s["holes"].failWith("no holes on a mesh surface", "holes");
    std::string file = s["mesh"].string();
    std::filesystem::path full = std::filesystem::path(baseDir_) / file;
    glm::dmat4 transform = s.has("transform") ? readTransform(s["transform"]) : glm::dmat4(1.0);
    auto groups = readMeshFile(full.string(), s["mesh"].where());
    int fixedMaterial = s.has("material") ? materialIndex(s["material"]) : -1;
    if (fixedMaterial >= 0) {  // one material for the whole mesh: one surface
      MeshFileGroup all;
      for (auto& g : groups)
        for (auto& f : g.faces) all.faces.push_back(std::move(f));
      groups = {std::move(all)};
    }
    for (auto& group : groups) {
      Surface surface;
      surface.fromMeshFile = true;
      surface.twoSided = twoSided;
      surface.where = s.where();
      surface.name = name;
      if (fixedMaterial >= 0) {
        surface.material = fixedMaterial;
      } else if (!group.material.empty()) {
        surface.name = name + "/" + group.material;
        surface.material = addMtlMaterial(s, group);
      } else {
        s.failWith("a \"material\" key or MTL materials on every face of " + file,
                   "faces without a material");
      }
      for (auto& face : group.faces) {
        for (auto& p : face.outer) p = glm::dvec3(transform * glm::dvec4(p, 1.0));
        surface.polygons.push_back(std::move(face));
      }
      dropDegenerateFaces(surface, s);
      scene_.surfaces.push_back(std::move(surface));
    }
  }

  int addMtlMaterial(const Node& s, const MeshFileGroup& group) {
    Material m;
    m.name = s.has("name") ? s["name"].string() + "/" + group.material : group.material;
    m.reflectance = group.kd.value_or(glm::dvec3(0.0));
    for (int i = 0; i < 3; ++i)
      if (!(m.reflectance[i] >= 0 && m.reflectance[i] < 1))
        s["mesh"].failWith("MTL Kd of \"" + group.material + "\" in [0, 1)",
                           std::to_string(m.reflectance[i]));
    // MTL Ke is radiance as renderers use it; a Lambertian emitter's exitance is pi times it.
    m.emission = M_PI * group.ke.value_or(glm::dvec3(0.0));
    for (int i = 0; i < 3; ++i)
      if (!(m.emission[i] >= 0 && std::isfinite(m.emission[i])))
        s["mesh"].failWith("MTL Ke of \"" + group.material + "\" finite and >= 0",
                           std::to_string(group.ke.value()[i]));
    m.diffuse = m.ambient = glm::dvec4(m.reflectance, 1.0);
    scene_.materials.push_back(m);
    return int(scene_.materials.size()) - 1;
  }

  /// Mesh files often carry a few zero-area faces; they carry no light, so they are
  /// dropped, and the loader says so.
  void dropDegenerateFaces(Surface& surface, const Node& s) {
    for (const auto& p : surface.polygons)
      for (const auto& q : p.outer)
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
          s["mesh"].failWith("finite vertex coordinates", "NaN or infinity");
    size_t before = surface.polygons.size();
    auto degenerate = [](const Polygon& p) {
      double size = ringDiameter(p.outer);
      return p.outer.size() < 3 || !(polygonArea(p) > kMinRelativeArea * size * size);
    };
    surface.polygons.erase(
        std::remove_if(surface.polygons.begin(), surface.polygons.end(), degenerate),
        surface.polygons.end());
    if (surface.polygons.empty())
      s["mesh"].failWith("faces of non-zero area", "only degenerate faces");
    if (surface.polygons.size() != before)
      scene_.warnings.push_back(s.where() + ": dropped " +
                                std::to_string(before - surface.polygons.size()) + " degenerate faces");
  }

  void validatePolygon(const Polygon& polygon, const Node& s) {
    double area = polygonArea(Polygon{polygon.outer, {}});
    double size = ringDiameter(polygon.outer);
    if (!(area > kMinRelativeArea * size * size))
      s["polygon"].failWith("a polygon of non-zero area", "area " + std::to_string(area));
    PlaneFrame frame = planeFrame(polygon.outer);
    for (size_t h = 0; h < polygon.holes.size(); ++h) {
      Node hole = s["holes"][h];
      const Ring& ring = polygon.holes[h];
      double holeArea = polygonArea(Polygon{ring, {}});
      if (!(holeArea > kMinRelativeArea * size * size))
        hole.failWith("a hole of non-zero area", "area " + std::to_string(holeArea));
      for (size_t k = 0; k < ring.size(); ++k) {
        if (std::abs(glm::dot(ring[k] - frame.origin, frame.normal)) > kPlanarity * size)
          hole[k].failWith("a hole vertex in the plane of its polygon",
                           "a point " + std::to_string(glm::dot(ring[k] - frame.origin,
                                                                frame.normal)) +
                               " away from it");
        if (!insideRing(frame, polygon.outer, ring[k]))
          hole[k].failWith("a hole vertex inside its polygon", "a point outside it");
      }
    }
  }

  Camera readCamera(const Node& n) {
    n.expectObject({"eye", "target", "up", "fov_y_deg"});
    Camera c;
    for (const char* key : {"eye", "target", "up"})
      if (!n.has(key)) n.failWith(std::string("a \"") + key + "\" key", "none");
    c.eye = n["eye"].vec3();
    c.target = n["target"].vec3();
    c.up = n["up"].vec3();
    if (n.has("fov_y_deg")) c.fovYDeg = n["fov_y_deg"].number(1e-3, 179.999, "(0, 180)");
    glm::dvec3 view = c.target - c.eye;
    if (glm::length(view) == 0) n["target"].failWith("a target away from the eye", "the eye");
    if (glm::length(glm::cross(view, c.up)) <= 1e-9 * glm::length(view) * glm::length(c.up))
      n["up"].failWith("an up vector not parallel to the view direction", "a parallel one");
    return c;
  }

  void readLightModel(const Node& n) {
    n.expectObject({"ambient", "local_viewer", "two_sided"});
    if (n.has("ambient")) scene_.lightModel.ambient = n["ambient"].color();
    if (n.has("local_viewer")) scene_.lightModel.localViewer = n["local_viewer"].boolean();
    if (n.has("two_sided")) scene_.lightModel.twoSided = n["two_sided"].boolean();
  }

  void readLights(const Node& n) {
    n.expectArray(0, "lights");
    constexpr size_t kMaxLights = 8;  // GL_MAX_LIGHTS in every OpenGL implementation
    if (n.size() > kMaxLights) n.fail("at most 8 lights (OpenGL's GL_MAX_LIGHTS)");
    for (size_t i = 0; i < n.size(); ++i) scene_.lights.push_back(readLight(n[i]));
  }

  Light readLight(const Node& n) {
    if (!n.value().is_object()) n.fail("an object");
    if (!n.has("type")) n.failWith("a \"type\" key", "none");
    Light l;
    std::string type = n["type"].string();
    std::vector<std::string> keys = {"type", "ambient", "diffuse", "specular"};
    if (type == "directional") {
      l.type = Light::Type::Directional;
      keys.push_back("direction");
    } else if (type == "point" || type == "spot") {
      l.type = type == "point" ? Light::Type::Point : Light::Type::Spot;
      for (const char* k : {"position", "attenuation"}) keys.push_back(k);
      if (type == "spot")
        for (const char* k : {"direction", "cutoff_deg", "exponent"}) keys.push_back(k);
    } else {
      n["type"].fail("\"directional\", \"point\" or \"spot\"");
    }
    n.expectObject(keys);
    auto required = [&](const char* key) {
      if (!n.has(key)) n.failWith(std::string("a \"") + key + "\" key for a " + type + " light",
                                  "none");
      return n[key];
    };
    if (l.type != Light::Type::Point) {
      Node d = required("direction");
      l.direction = d.vec3();
      if (glm::length(l.direction) == 0) d.fail("a non-zero direction");
    }
    if (l.type != Light::Type::Directional) l.position = required("position").vec3();
    if (n.has("ambient")) l.ambient = n["ambient"].color();
    if (n.has("diffuse")) l.diffuse = n["diffuse"].color();
    if (n.has("specular")) l.specular = n["specular"].color();
    if (n.has("attenuation")) {
      l.attenuation = nonNegativeRgb(n["attenuation"], "an attenuation coefficient >= 0");
      if (l.attenuation == glm::dvec3(0.0))
        n["attenuation"].fail("at least one non-zero coefficient");
    }
    if (l.type == Light::Type::Spot) {
      l.cutoffDeg = required("cutoff_deg").number(0, 90, "[0, 90]");
      if (n.has("exponent")) l.exponent = n["exponent"].number(0, 128, "[0, 128]");
    }
    return l;
  }

  Fog readFog(const Node& n) {
    n.expectObject({"mode", "color", "start", "end", "density"});
    Fog f;
    if (!n.has("mode")) n.failWith("a \"mode\" key", "none");
    std::string mode = n["mode"].string();
    if (mode == "linear") f.mode = Fog::Mode::Linear;
    else if (mode == "exp") f.mode = Fog::Mode::Exp;
    else if (mode == "exp2") f.mode = Fog::Mode::Exp2;
    else n["mode"].fail("\"linear\", \"exp\" or \"exp2\"");
    if (n.has("color")) f.color = n["color"].color();
    if (n.has("start")) f.start = n["start"].number();
    if (n.has("end")) f.end = n["end"].number();
    if (n.has("density")) f.density = n["density"].number(0, HUGE_VAL, "[0, inf)");
    if (f.mode == Fog::Mode::Linear && f.end == f.start)
      n.failWith("linear fog with end != start", "end = start = " + std::to_string(f.end));
    return f;
  }

  void readSolver(const Node& n) {
    n.expectObject({"max_element_edge", "max_patch_edge", "hemicube_resolution",
                    "emitter_hemicube_resolution", "tolerance",
                    "seed", "max_shots", "time_limit", "overshoot", "exposure", "emitter_samples",
                    "shooter_samples", "proximity_samples", "factor_cache_mb", "cut_contacts",
                    "adaptive", "min_element_edge", "contrast", "vertex_direct", "max_elements"});
    SolverBlock& b = scene_.solver;
    if (n.has("max_element_edge"))
      b.maxElementEdge = n["max_element_edge"].number(1e-300, HUGE_VAL, "(0, inf)");
    if (n.has("max_patch_edge"))
      b.maxPatchEdge = n["max_patch_edge"].number(1e-300, HUGE_VAL, "(0, inf)");
    if (n.has("tolerance")) b.tolerance = n["tolerance"].number(1e-300, 1, "(0, 1]");
    if (n.has("time_limit")) b.timeLimit = n["time_limit"].number(1e-300, HUGE_VAL, "(0, inf)");
    if (n.has("overshoot")) b.overshoot = n["overshoot"].number(1, 2, "[1, 2]");
    if (n.has("exposure")) b.exposure = n["exposure"].number(1e-300, HUGE_VAL, "(0, inf)");
    if (n.has("cut_contacts")) b.cutContacts = n["cut_contacts"].boolean();
    if (n.has("adaptive")) b.adaptive = n["adaptive"].boolean();
    if (n.has("vertex_direct")) b.vertexDirect = n["vertex_direct"].boolean();
    if (n.has("min_element_edge"))
      b.minElementEdge = n["min_element_edge"].number(1e-300, HUGE_VAL, "(0, inf)");
    if (n.has("contrast")) b.contrast = n["contrast"].number(1e-6, 1, "[1e-6, 1]");
    if (n.has("proximity_samples"))
      b.proximitySamples = n["proximity_samples"].number(0, 65536, "[0, 65536]");
    if (n.has("factor_cache_mb"))
      b.factorCacheMb = n["factor_cache_mb"].number(0, 1e9, "[0, 1e9]");
    for (auto [key, slot] : {std::pair{"emitter_samples", &b.emitterSamples},
                             std::pair{"shooter_samples", &b.shooterSamples}}) {
      if (!n.has(key)) continue;
      Node m = n[key];
      double x = m.number(1, 65536, "[1, 65536]");
      if (x != std::floor(x)) m.fail("a whole number");
      *slot = int(x);
    }
    if (n.has("max_elements")) {
      Node m = n["max_elements"];
      double x = m.number(1, 1e12, "[1, 1e12]");
      if (x != std::floor(x)) m.fail("a whole number");
      b.maxElements = long(x);
    }
    if (n.has("max_shots")) {
      Node m = n["max_shots"];
      double x = m.number(1, 1e15, "[1, 1e15]");
      if (x != std::floor(x)) m.fail("a whole number");
      b.maxShots = long(x);
    }
    for (auto [key, slot] : {std::pair{"hemicube_resolution", &b.hemicubeResolution},
                             std::pair{"emitter_hemicube_resolution", &b.emitterHemicubeResolution}}) {
      if (!n.has(key)) continue;
      Node r = n[key];
      double x = r.number(2, 8192, "[2, 8192]");
      if (x != std::floor(x) || int(x) % 2) r.fail("an even whole number");
      *slot = int(x);
    }
    if (n.has("seed")) {
      Node s = n["seed"];
      double x = s.number(0, 4294967295.0, "[0, 2^32)");
      if (x != std::floor(x)) s.fail("a whole number");
      b.seed = unsigned(x);
    }
  }

  Scene& scene_;
  std::string file_, baseDir_;
};

/// Coordinates beyond this magnitude (scene units) are refused: squared areas and the
/// mesher's predicates overflow double precision long before 1e77.
constexpr double kMaxCoordinate = 1e15;
/// A scene smaller than this (its bounding box's diagonal, scene units) is refused: squared
/// lengths would fall into denormals.
constexpr double kMinSceneSize = 1e-12;

/// Every point within ±kMaxCoordinate and the scene no smaller than kMinSceneSize.
void checkScale(const Scene& scene) {
  for (const auto& s : scene.surfaces)
    for (const auto& p : s.polygons)
      for (const auto& q : p.outer)
        if (std::abs(q.x) > kMaxCoordinate || std::abs(q.y) > kMaxCoordinate || std::abs(q.z) > kMaxCoordinate) {
          char found[96];
          std::snprintf(found, sizeof found, "the point (%g, %g, %g)", q.x, q.y, q.z);
          throw inputError(s.where + " (" + s.name + ")",
                           "coordinates within ±1e15 scene units (choose larger units or scale the surface down)",
                           found);
        }
  if (!scene.surfaces.empty() && !(scene.diagonal() >= kMinSceneSize))
    throw inputError(scene.path + ": surfaces", "a scene at least 1e-12 scene units across (choose smaller units)",
                     "one " + std::to_string(scene.diagonal()) + " across");
}

}  // namespace

bool Scene::hasEmitter() const {
  for (const auto& s : surfaces)
    if (materials[s.material].emits()) return true;
  return false;
}

double Scene::diagonal() const {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const auto& s : surfaces)
    for (const auto& p : s.polygons)
      for (const auto& q : p.outer) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
      }
  return lo.x <= hi.x ? glm::length(hi - lo) : 0.0;
}

Scene parseScene(const std::string& text, const std::string& path, const std::string& baseDir) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann's message reads "[json.exception.parse_error.101] parse error at line L,
    // column C: ..."; keep what follows the bracket.
    std::string what = e.what();
    auto at = what.find("] ");
    throw InputError(path + ": " + (at == std::string::npos ? what : what.substr(at + 2)));
  } catch (const json::out_of_range& e) {
    // A number too large for a double (how NaN and infinity sneak into JSON): say where.
    std::string what = e.what();
    auto q = what.find('\''), r = what.rfind('\'');
    std::string literal = q != std::string::npos && r > q ? what.substr(q + 1, r - q - 1) : "";
    throw inputError(path + ": " + lineColumn(text, literal), "finite numbers",
                     "'" + literal + "', which overflows a double");
  }
  Scene scene;
  scene.path = path;
  SceneReader reader(scene, path, baseDir);
  reader.read(root);
  checkScale(scene);
  return scene;
}

Scene loadScene(const std::string& path) {
  const std::string text = readInputFile(path, "a readable scene file", kMaxSceneFileBytes);
  std::string base = std::filesystem::path(path).parent_path().string();
  return parseScene(text, path, base.empty() ? "." : base);
}

}  // namespace rad
