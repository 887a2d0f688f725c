// Reads and validates the version-1 scene file of DESIGN.md: the top level here, each section
// in its own file (scene_materials, scene_surfaces, scene_display, scene_solver).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>

#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/scene/readers/scene_loader.h"
#include "mesh/scene/readers/scene_sections.h"

namespace rad {
namespace {

using scene_file::json;
using scene_file::Node;

/// "line L, column C" of the first occurrence of `token` in `text`.
std::string lineColumn(const std::string& text, const std::string& token) {
  size_t at = token.empty() ? std::string::npos : text.find(token);
  if (at == std::string::npos) return "somewhere";
  size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  size_t lineStart = text.rfind('\n', at);
  size_t column = at - (lineStart == std::string::npos ? 0 : lineStart + 1) + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

/// A JSON syntax error, as nlohmann says it: "[json.exception.parse_error.101] parse error at
/// line L, column C: ..."; what follows the bracket is kept.
InputError syntaxError(const json::parse_error& e, const std::string& path) {
  std::string what = e.what();
  auto at = what.find("] ");
  return InputError(path + ": " + (at == std::string::npos ? what : what.substr(at + 2)));
}

/// A number too large for a double (how NaN and infinity sneak into JSON), said where.
InputError overflowError(const json::out_of_range& e, const std::string& text, const std::string& path) {
  std::string what = e.what();
  auto q = what.find('\''), r = what.rfind('\'');
  std::string literal = q != std::string::npos && r > q ? what.substr(q + 1, r - q - 1) : "";
  return inputError(path + ": " + lineColumn(text, literal), "finite numbers",
                    "'" + literal + "', which overflows a double");
}

/// The JSON text parsed; a syntax error or a number too large for a double says where.
json parseJson(const std::string& text, const std::string& path) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw syntaxError(e, path);
  } catch (const json::out_of_range& e) {
    throw overflowError(e, text, path);
  }
}

/// The display-only sections, those present.
void readDisplay(const Node& n, Scene& scene) {
  if (n.has("camera")) scene.camera = scene_file::readCamera(n["camera"]);
  if (n.has("light_model")) scene_file::readLightModel(n["light_model"], scene.lightModel);
  if (n.has("lights")) scene_file::readLights(n["lights"], scene.lights);
  if (n.has("fog")) scene.fog = scene_file::readFog(n["fog"]);
}

/// Every section of the scene file, in the order they are checked.
void readScene(const Node& n, const std::string& baseDir, Scene& scene) {
  n.expectObject({"version", "units", "materials", "surfaces", "camera", "light_model",
                  "lights", "fog", "solver"});
  if (!n.has("version")) n.failWith("a \"version\" key", "none");
  if (n["version"].value() != 1) n["version"].fail("version 1");
  if (n.has("units")) scene.units = n["units"].string();
  // A scene of mesh files whose MTL files give every material needs no "materials" object.
  if (n.has("materials")) scene_file::readMaterials(n["materials"], scene);
  if (!n.has("surfaces")) n.failWith("a \"surfaces\" array", "none");
  scene_file::readSurfaces(n["surfaces"], baseDir, scene);
  readDisplay(n, scene);
  if (n.has("solver")) scene_file::readSolver(n["solver"], scene.solver);
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& path, const std::string& baseDir) {
  const json root = parseJson(text, path);
  Scene scene;
  scene.path = path;
  readScene(Node(root, path, ""), baseDir, scene);
  scene_file::checkScale(scene);
  return scene;
}

Scene loadScene(const std::string& path) {
  const std::string text = readInputFile(path, "a readable scene file", kMaxSceneFileBytes);
  std::string base = std::filesystem::path(path).parent_path().string();
  return parseScene(text, path, base.empty() ? "." : base);
}

}  // namespace rad
