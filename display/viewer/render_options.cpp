// What a render looks from and at: the --camera text, the effective camera and exposure, the
// view and projection matrices, and the image size check.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "display/viewer/viewer_internal.h"
#include "mesh/base/error.h"
#include "mesh/results/default_camera.h"
#include "mesh/scene/camera.h"

namespace rad::viewer {
namespace {

/// The numbers given for each key of the --camera text, in order.
using CameraValues = std::map<std::string, std::vector<double>>;

/// The --camera error: what the text should be, and `why` it is not.
InputError badCamera(const std::string& why) {
  return inputError("--camera", "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F (any subset)", why);
}

/// Throws unless `key` is one of the camera's and not given before.
void checkCameraKey(const std::string& key, const CameraValues& values) {
  if (key != "eye" && key != "target" && key != "up" && key != "fov")
    throw badCamera("the unknown key \"" + key + "\"");
  if (values.count(key)) throw badCamera("\"" + key + "\" twice");
}

/// The key a "key=number" token starts (checked: known, given once), or "" for a plain number.
std::string startKey(const std::string& token, CameraValues& values) {
  const size_t eq = token.find('=');
  if (eq == std::string::npos) return "";
  const std::string key = token.substr(0, eq);
  checkCameraKey(key, values);
  values[key];
  return key;
}

/// A finite number, the whole of `number`; `key` names where it belongs.
double cameraNumber(const std::string& number, const std::string& key) {
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || !std::isfinite(v))
    throw badCamera("\"" + number + "\" where a finite number belongs (in " + key + ")");
  return v;
}

/// Reads one comma-separated token of the text into `values`: a "key=number" starts that key,
/// a plain number belongs to `current`, the last key named.
void readCameraToken(const std::string& text, const std::string& token, std::string& current,
                     CameraValues& values) {
  std::string key = startKey(token, values), number = token;
  if (!key.empty()) {
    current = key;
    number = token.substr(token.find('=') + 1);
  }
  if (current.empty()) throw badCamera("'" + text + "' (no key before \"" + token + "\")");
  values[current].push_back(cameraNumber(number, current));
}

/// Splits the text at commas into numbers, each belonging to the last key named.
CameraValues readCameraValues(const std::string& text) {
  CameraValues values;
  std::string current, token;
  std::stringstream s(text);
  while (std::getline(s, token, ',')) readCameraToken(text, token, current, values);
  if (values.empty()) throw badCamera("'" + text + "'");
  return values;
}

/// Throws unless `key` has its count of numbers: one for fov, three for the others.
void checkValueCount(const std::string& key, const std::vector<double>& v) {
  const size_t want = key == "fov" ? 1 : 3;
  if (v.size() != want)
    throw badCamera(std::to_string(v.size()) + " number(s) for " + key + " where " +
                    std::to_string(want) + " belong");
}

/// The camera's point or direction that `key` names (eye, target, up), or null (fov).
glm::dvec3* cameraVector(Camera& c, const std::string& key) {
  return key == "eye" ? &c.eye : key == "target" ? &c.target : key == "up" ? &c.up : nullptr;
}

/// Sets one key's numbers in `c`: three for eye, target or up, one for fov.
void applyCameraValue(const std::string& key, const std::vector<double>& v, Camera& c) {
  checkValueCount(key, v);
  if (key == "fov") c.fovYDeg = v[0];
  if (glm::dvec3* vec = cameraVector(c, key)) *vec = glm::dvec3(v[0], v[1], v[2]);
}

/// Sets the keys' values in `c`: three numbers for eye, target and up, one for fov.
void applyCameraValues(const CameraValues& values, Camera& c) {
  for (const auto& [key, v] : values) applyCameraValue(key, v, c);
}

/// Corner `i` (0..7, bits x, y, z: high or low) of the box from lo to hi.
glm::dvec3 boxCorner(int i, const glm::dvec3& lo, const glm::dvec3& hi) {
  return glm::dvec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
}

/// The nearest and farthest depth along the view of the box's corners (view: world to eye).
std::pair<double, double> depthRange(const glm::dmat4& view, const glm::dvec3& lo, const glm::dvec3& hi) {
  double nearest = std::numeric_limits<double>::infinity(), farthest = 0;
  for (int i = 0; i < 8; ++i) {
    const double depth = -(view * glm::dvec4(boxCorner(i, lo, hi), 1.0)).z;
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  return {nearest, farthest};
}

/// The camera's perspective for a width x height picture of the mesh, near and far fitted to
/// the bounding box's corners along the view axis (view: world to eye).
glm::dmat4 fittedPerspective(const ResultFile& mesh, const Camera& c, const glm::dmat4& view, int width,
                             int height) {
  const auto [nearest, farthest] = depthRange(view, mesh.boundsMin, mesh.boundsMax);
  const double size = std::max(glm::length(mesh.boundsMax - mesh.boundsMin), 1e-9);
  const double zFar = std::max(farthest, 0.0) * 1.01 + 1e-3 * size;
  const double zNear = std::max(nearest * 0.99, zFar * 1e-4);
  return glm::perspective(glm::radians(c.fovYDeg), double(width) / height, zNear, zFar);
}

}  // namespace

Camera parseCamera(const std::string& text, const Camera& base) {
  Camera c = base;
  applyCameraValues(readCameraValues(text), c);
  checkCamera(c, "--camera");
  return c;
}

Camera effectiveCamera(const ResultFile& mesh, const RenderOptions& options) {
  if (options.camera) return *options.camera;
  if (mesh.camera) return *mesh.camera;
  return defaultCamera(mesh);
}

double effectiveExposure(const ResultFile& mesh, const RenderOptions& options) {
  if (options.exposure) return *options.exposure;
  return mesh.exposure.value_or(1.0);
}

glm::mat4 viewProjection(const ResultFile& mesh, const Camera& c, int width, int height,
                         glm::mat4* projection, glm::mat4* view) {
  const glm::dmat4 v = glm::lookAt(c.eye, c.target, c.up);
  const glm::dmat4 p = fittedPerspective(mesh, c, v, width, height);
  if (projection) *projection = glm::mat4(p);
  if (view) *view = glm::mat4(v);
  return glm::mat4(p * v);
}

namespace internal {

FrameView frameView(const ResultFile& mesh, const Camera& c, const RenderOptions& o) {
  FrameView f;
  f.width = o.width * o.ssaa;
  f.height = o.height * o.ssaa;
  f.mvp = viewProjection(mesh, c, f.width, f.height, &f.projection, &f.view);
  return f;
}

void checkSize(const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.ssaa < 1 || int64_t(o.width) * o.ssaa > raster::kMaxSize ||
      int64_t(o.height) * o.ssaa > raster::kMaxSize)
    throw inputError("image size", "width and height times --ssaa in 1.." + std::to_string(raster::kMaxSize),
                     std::to_string(o.width) + "x" + std::to_string(o.height) + " at --ssaa " +
                         std::to_string(o.ssaa));
}

}  // namespace internal
}  // namespace rad::viewer
