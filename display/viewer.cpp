#include "display/viewer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <stb_image.h>
#include <stb_image_write.h>

#include "display/raster.h"
#include "mesh/camera.h"
#include "mesh/color.h"
#include "mesh/error.h"
#include "mesh/mesh_settings.h"
#include "mesh/output_file.h"
#include "mesh/ply_reader.h"

namespace rad::viewer {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Linear value of each sRGB display byte: the inverse of mesh/color.h's srgbEncode (found by
/// bisection on it, so the curve has one home).
const std::array<double, 256>& srgbDecodeTable() {
  static const std::array<double, 256> table = [] {
    std::array<double, 256> t{};
    for (int b = 0; b < 256; ++b) {
      double lo = 0, hi = 1, want = b / 255.0;
      for (int i = 0; i < 60; ++i) {
        double mid = 0.5 * (lo + hi);
        (srgbEncode(mid) < want ? lo : hi) = mid;
      }
      t[b] = 0.5 * (lo + hi);
    }
    return t;
  }();
  return table;
}

uint8_t toByte(float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

/// Box-filters a (width·k) × (height·k) bottom-up picture down to width × height, top row first:
/// each value is taken to linear light by `decode`, averaged, and brought back by `encode`.
template <class T, class Decode, class Encode>
std::vector<T> boxFilter(const std::vector<T>& big, int width, int height, int k, Decode decode,
                         Encode encode) {
  std::vector<T> out(size_t(width) * height * 3);
  if (k == 1) {  // only the flip: no round trip through linear light
    for (int y = 0; y < height; ++y)
      std::copy_n(&big[size_t(height - 1 - y) * width * 3], width * 3, &out[size_t(y) * width * 3]);
    return out;
  }
  const int bigWidth = width * k;
  const double norm = 1.0 / (k * k);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (int j = 0; j < k; ++j)
          for (int i = 0; i < k; ++i) sum += decode(big[(size_t(y * k + j) * bigWidth + x * k + i) * 3 + c]);
        out[(size_t(height - 1 - y) * width + x) * 3 + c] = encode(sum * norm);
      }
  return out;
}

/// Bytes (sRGB): averaged in linear light.
std::vector<uint8_t> downsampleBytes(const std::vector<uint8_t>& big, int width, int height, int k) {
  const auto& table = srgbDecodeTable();
  return boxFilter(big, width, height, k, [&](uint8_t v) { return table[v]; },
                   [](double x) { return uint8_t(std::lround(255 * srgbEncode(x))); });
}

/// Linear floats: a plain average.
std::vector<float> downsampleFloats(const std::vector<float>& big, int width, int height, int k) {
  return boxFilter(big, width, height, k, [](float v) { return double(v); },
                   [](double x) { return float(x); });
}

/// The raster core's picture of the draw list: bytes and optionally radiance, bottom-up.
void renderSoftware(const detail::DrawList& list, const glm::mat4& mvp, int width, int height,
                    Shading shade, bool wireframe, std::vector<uint8_t>& rgb,
                    std::vector<float>* radiance, bool cullBack) {
  raster::Target target(width, height, /*withItem=*/false, /*withColor=*/true);
  raster::State state;
  state.shade = shade == Shading::Flat ? raster::Shade::Flat : raster::Shade::Smooth;
  if (cullBack) state.cull = raster::Cull::Back;
  std::vector<glm::vec4> clip;
  raster::transform(mvp, list.positions, clip);
  const size_t n = list.positions.size();
  raster::drawTriangles(target, state, clip.data(), n, nullptr, n / 3, nullptr, list.display.data());
  if (wireframe && cullBack) {
    // As OpenGL culls before GL_LINE rasterisation: only the front faces' edges.
    std::vector<uint32_t> front;
    for (uint32_t t = 0; 3 * size_t(t) + 2 < n; ++t)
      if (detail::frontFacing(clip[3 * t], clip[3 * t + 1], clip[3 * t + 2]))
        front.insert(front.end(), {3 * t, 3 * t + 1, 3 * t + 2});
    detail::drawSoftwareWireframe(target, clip, &front);
  } else if (wireframe) {
    detail::drawSoftwareWireframe(target, clip, nullptr);
  }
  rgb.resize(size_t(width) * height * 3);
  for (size_t p = 0; p < target.color.size(); ++p)
    for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = toByte(target.color[p][c]);
  if (!radiance) return;
  target.clear();
  raster::drawTriangles(target, state, clip.data(), n, nullptr, n / 3, nullptr, list.radiance.data());
  radiance->resize(size_t(width) * height * 3);
  for (size_t p = 0; p < target.color.size(); ++p)
    for (int c = 0; c < 3; ++c) (*radiance)[p * 3 + c] = target.color[p][c];
}

void writeWithStb(const std::string& path, const std::function<int(std::ostream&)>& encode,
                  const char* what) {
  writeFileAtomically(path, [&](std::ostream& out) {
    if (!encode(out)) throw inputError(path, std::string("a ") + what + " image encoded", "an encoder failure");
  });
}

void toStream(void* context, void* data, int size) {
  static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}

}  // namespace

Camera parseCamera(const std::string& text, const Camera& base) {
  const std::string where = "--camera";
  const std::string expected = "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F (any subset)";
  auto bad = [&](const std::string& why) { return inputError(where, expected, why); };
  std::map<std::string, std::vector<double>> values;
  std::string current;
  std::stringstream s(text);
  std::string token;
  while (std::getline(s, token, ',')) {
    size_t eq = token.find('=');
    std::string number = token;
    if (eq != std::string::npos) {
      current = token.substr(0, eq);
      if (current != "eye" && current != "target" && current != "up" && current != "fov")
        throw bad("the unknown key \"" + current + "\"");
      if (values.count(current)) throw bad("\"" + current + "\" twice");
      values[current];
      number = token.substr(eq + 1);
    }
    if (current.empty()) throw bad("'" + text + "' (no key before \"" + token + "\")");
    char* end = nullptr;
    double v = std::strtod(number.c_str(), &end);
    if (number.empty() || *end != '\0' || !std::isfinite(v))
      throw bad("\"" + number + "\" where a finite number belongs (in " + current + ")");
    values[current].push_back(v);
  }
  if (values.empty()) throw bad("'" + text + "'");
  Camera c = base;
  for (const auto& [key, v] : values) {
    size_t want = key == "fov" ? 1 : 3;
    if (v.size() != want)
      throw bad(std::to_string(v.size()) + " number(s) for " + key + " where " + std::to_string(want) +
                " belong");
    if (key == "fov") c.fovYDeg = v[0];
    glm::dvec3* vec = key == "eye" ? &c.eye : key == "target" ? &c.target : key == "up" ? &c.up : nullptr;
    if (vec) *vec = glm::dvec3(v[0], v[1], v[2]);
  }
  checkCamera(c, where);
  return c;
}

Camera effectiveCamera(const ResultFile& mesh, const RenderOptions& options) {
  if (options.camera) return *options.camera;
  if (mesh.camera) return *mesh.camera;
  return defaultCamera(mesh.boundsMin, mesh.boundsMax);
}

double effectiveExposure(const ResultFile& mesh, const RenderOptions& options) {
  if (options.exposure) return *options.exposure;
  return mesh.exposure.value_or(1.0);
}

glm::mat4 viewProjection(const ResultFile& mesh, const Camera& c, int width, int height,
                         glm::mat4* projection, glm::mat4* view) {
  glm::dmat4 v = glm::lookAt(c.eye, c.target, c.up);
  // Near and far fitted to the bounding box's corners along the view axis.
  double nearest = std::numeric_limits<double>::infinity(), farthest = 0;
  for (int i = 0; i < 8; ++i) {
    glm::dvec3 p((i & 1) ? mesh.boundsMax.x : mesh.boundsMin.x, (i & 2) ? mesh.boundsMax.y : mesh.boundsMin.y,
                 (i & 4) ? mesh.boundsMax.z : mesh.boundsMin.z);
    double depth = -(v * glm::dvec4(p, 1.0)).z;
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  double size = std::max(glm::length(mesh.boundsMax - mesh.boundsMin), 1e-9);
  double zFar = std::max(farthest, 0.0) * 1.01 + 1e-3 * size;
  double zNear = std::max(nearest * 0.99, zFar * 1e-4);
  glm::dmat4 p = glm::perspective(glm::radians(c.fovYDeg), double(width) / height, zNear, zFar);
  if (projection) *projection = glm::mat4(p);
  if (view) *view = glm::mat4(v);
  return glm::mat4(p * v);
}

namespace detail {

bool frontFacing(const glm::vec4& a, const glm::vec4& b, const glm::vec4& c) {
  const glm::dvec3 p(a.x, a.y, a.w), q(b.x, b.y, b.w), r(c.x, c.y, c.w);
  return glm::dot(p, glm::cross(q, r)) > 0;
}

void drawSoftwareWireframe(raster::Target& target, const std::vector<glm::vec4>& clip,
                           const std::vector<uint32_t>* triangles) {
  const size_t triangleCount = triangles ? triangles->size() / 3 : clip.size() / 3;
  const raster::State state;
  const glm::vec4 colour(glm::vec3(kWireByte / 255.0f), 1.0f);
  const double W = target.width, H = target.height;
  for (size_t t = 0; t < triangleCount; ++t) {
    uint32_t v[3];
    for (int k = 0; k < 3; ++k) v[k] = triangles ? (*triangles)[3 * t + k] : uint32_t(3 * t + k);
    const uint32_t edges[6] = {v[0], v[1], v[1], v[2], v[2], v[0]};
    // Bias: the triangle's largest window-depth slope per pixel (its depth plane, when all three
    // vertices are in front of the eye) plus kWireDepthBias, as glPolygonOffset(1, 1) pushes the
    // fill back in OpenGL.
    double slope = 0;
    glm::dvec3 w[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    bool inFront = true;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec4 c(clip[v[k]]);
      if (c.w <= 0) inFront = false;
      else w[k] = glm::dvec3((c.x / c.w + 1) * 0.5 * W, (c.y / c.w + 1) * 0.5 * H, (c.z / c.w + 1) * 0.5);
    }
    if (inFront) {
      const glm::dvec3 n = glm::cross(w[1] - w[0], w[2] - w[0]);
      if (std::abs(n.z) > 1e-12) slope = std::max(std::abs(n.x / n.z), std::abs(n.y / n.z));
    }
    raster::drawLines(target, state, clip.data(), clip.size(), edges, 3, colour,
                      float(slope + kWireDepthBias));
  }
}

DrawList buildDrawList(const ResultFile& mesh, Shading shade, double exposure, bool storedColours) {
  DrawList list;
  const size_t n = mesh.faces.size() * 3;
  list.positions.reserve(n);
  list.display.reserve(n);
  list.radiance.reserve(n);
  auto displayColour = [&](const glm::dvec3& b) {
    return glm::vec4(displayByte(b.x, exposure) / 255.0f, displayByte(b.y, exposure) / 255.0f,
                     displayByte(b.z, exposure) / 255.0f, 1.0f);
  };
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int corner = 0; corner < 3; ++corner) {
      int v = mesh.faces[f][corner];
      const glm::dvec3& b = shade == Shading::Flat ? mesh.faceRadiosity[f] : mesh.vertexRadiosity[v];
      list.positions.push_back(mesh.positions[v]);
      if (storedColours) {
        const auto& c = mesh.vertexColour[v];
        list.display.push_back(glm::vec4(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f));
      } else {
        list.display.push_back(displayColour(b));
      }
      list.radiance.push_back(glm::vec4(glm::dvec3(b / kPi), 1.0));
    }
  return list;
}

}  // namespace detail

namespace {
void checkSize(const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.ssaa < 1 || int64_t(o.width) * o.ssaa > raster::kMaxSize ||
      int64_t(o.height) * o.ssaa > raster::kMaxSize)
    throw inputError("image size", "width and height times --ssaa in 1.." + std::to_string(raster::kMaxSize),
                     std::to_string(o.width) + "x" + std::to_string(o.height) + " at --ssaa " +
                         std::to_string(o.ssaa));
}

/// Checks that every face has a surface index of `scene`; where names the mode.
void checkFaceSurfaces(const ResultFile& mesh, const Scene& scene, const std::string& where) {
  if (mesh.faceSurface.size() != mesh.faces.size())
    throw inputError(mesh.path, "a result with the face property `surface` (for " + where + ")", "none");
  for (size_t f = 0; f < mesh.faceSurface.size(); ++f)
    if (mesh.faceSurface[f] < 0 || size_t(mesh.faceSurface[f]) >= scene.surfaces.size())
      throw inputError(mesh.path + ": face " + std::to_string(f) + ": surface",
                       "a surface index of " + scene.path + " (0.." +
                           std::to_string(int(scene.surfaces.size()) - 1) + ")",
                       std::to_string(mesh.faceSurface[f]));
}

/// A ResultFile carrying only what camera fitting uses: the bounds and the scene's camera.
ResultFile boundsOnly(const LocalScene& local) {
  ResultFile m;
  m.path = local.scene.path;
  m.boundsMin = local.boundsMin;
  m.boundsMax = local.boundsMax;
  m.camera = local.scene.camera;
  return m;
}
}  // namespace

Image render(const ResultFile& mesh, const RenderOptions& o) {
  checkSize(o);
  const int w = o.width * o.ssaa, h = o.height * o.ssaa;
  glm::mat4 projection, view;
  glm::mat4 mvp = viewProjection(mesh, effectiveCamera(mesh, o), w, h, &projection, &view);
  // Gouraud at the file's own exposure shows the file's colours, which carry the ambient term of
  // an unconverged solve; anything else is computed from the radiosities.
  const bool stored = o.shade == Shading::Smooth && !o.exposure && mesh.exposure &&
                      !mesh.vertexColour.empty();
  detail::DrawList list = detail::buildDrawList(mesh, o.shade, effectiveExposure(mesh, o), stored);
  std::vector<uint8_t> rgb;
  std::vector<float> radiance;
  if (o.backend == Backend::Software)
    renderSoftware(list, mvp, w, h, o.shade, o.wireframe, rgb, o.radiance ? &radiance : nullptr,
                   o.cullBack);
  else
    detail::renderOsMesa(list, projection, view, w, h, o.shade, o.wireframe, rgb,
                         o.radiance ? &radiance : nullptr, o.cullBack);
  Image image;
  image.width = o.width;
  image.height = o.height;
  image.rgb = downsampleBytes(rgb, o.width, o.height, o.ssaa);
  if (o.radiance) image.radiance = downsampleFloats(radiance, o.width, o.height, o.ssaa);
  return image;
}

LocalScene prepareLocalScene(Scene scene) {
  if (scene.lights.empty())
    throw inputError(scene.path, "a scene with lights for --mode local", "none");
  LocalScene local;
  local.mesh = buildPatchMesh(scene, resolveMeshSettings(scene, {}));
  local.scene = std::move(scene);
  local.boundsMin = glm::dvec3(std::numeric_limits<double>::infinity());
  local.boundsMax = -local.boundsMin;
  for (auto v : local.mesh.mesh.vertices()) {
    glm::dvec3 p = PatchMesh::toGlm(local.mesh.mesh.point(v));
    local.boundsMin = glm::min(local.boundsMin, p);
    local.boundsMax = glm::max(local.boundsMax, p);
  }
  if (local.mesh.elementCount() == 0) throw inputError(local.scene.path, "a scene with surfaces", "none");
  return local;
}

LocalScene loadLocalScene(const std::string& path) { return prepareLocalScene(loadScene(path)); }

Camera effectiveCamera(const LocalScene& local, const RenderOptions& options) {
  return effectiveCamera(boundsOnly(local), options);
}

namespace detail {

LocalDrawList buildLocalDrawList(const LocalScene& local, Shading shade) {
  const PatchMesh& pm = local.mesh;
  const Scene& scene = local.scene;
  // Elements grouped by surface, one material batch per surface.
  std::vector<std::vector<int>> bySurface(scene.surfaces.size());
  for (int e = 0; e < pm.elementCount(); ++e) bySurface.at(size_t(pm.surface(e))).push_back(e);
  LocalDrawList list;
  list.positions.reserve(size_t(pm.elementCount()) * 3);
  list.normals.reserve(size_t(pm.elementCount()) * 3);
  for (size_t s = 0; s < bySurface.size(); ++s) {
    if (bySurface[s].empty()) continue;
    const Material& m = scene.materials.at(size_t(scene.surfaces[s].material));
    LocalBatch b;
    b.first = int(list.positions.size());
    b.ambient = glm::vec4(m.ambient);
    b.diffuse = glm::vec4(m.diffuse);
    b.specular = glm::vec4(m.specular);
    b.shininess = float(m.shininess);
    // Emission normalised to full brightness: E / max component (lamps show their hue at full
    // brightness; radiosity units have no fixed display scale).
    const double peak = std::max({m.emission.x, m.emission.y, m.emission.z});
    b.emission = peak > 0 ? glm::vec4(glm::vec3(m.emission / peak), 1.0f) : glm::vec4(0, 0, 0, 1);
    for (int e : bySurface[s]) {
      const TriMesh::FaceHandle f(e);
      const glm::vec3 faceNormal(pm.normal(e));
      for (auto v : pm.mesh.fv_range(f)) {
        list.positions.push_back(glm::vec3(PatchMesh::toGlm(pm.mesh.point(v))));
        list.normals.push_back(shade == Shading::Flat ? faceNormal
                                                      : glm::vec3(PatchMesh::toGlm(pm.mesh.normal(v))));
      }
    }
    b.count = int(list.positions.size()) - b.first;
    list.batches.push_back(b);
  }
  return list;
}

HybridDrawList buildHybridDrawList(const ResultFile& mesh, const Scene& scene, Shading shade,
                                   double exposure, bool storedColours) {
  const DrawList base = buildDrawList(mesh, shade, exposure, storedColours);
  std::vector<std::vector<size_t>> bySurface(scene.surfaces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) bySurface[size_t(mesh.faceSurface[f])].push_back(f);
  HybridDrawList list;
  list.positions.reserve(base.positions.size());
  list.normals.reserve(base.positions.size());
  list.colours.reserve(base.positions.size());
  for (size_t s = 0; s < bySurface.size(); ++s) {
    if (bySurface[s].empty()) continue;
    const Material& m = scene.materials.at(size_t(scene.surfaces[s].material));
    LocalBatch b;
    b.first = int(list.positions.size());
    b.specular = glm::vec4(m.specular);
    b.shininess = float(m.shininess);
    for (size_t f : bySurface[s]) {
      const auto& face = mesh.faces[f];
      const glm::vec3 p0 = mesh.positions[size_t(face[0])], p1 = mesh.positions[size_t(face[1])],
                      p2 = mesh.positions[size_t(face[2])];
      glm::vec3 faceNormal = glm::cross(p1 - p0, p2 - p0);
      const float len = glm::length(faceNormal);
      faceNormal = len > 0 ? faceNormal / len : glm::vec3(0, 0, 1);
      for (int corner = 0; corner < 3; ++corner) {
        const size_t k = 3 * f + size_t(corner);
        list.positions.push_back(base.positions[k]);
        list.colours.push_back(base.display[k]);
        list.normals.push_back(shade == Shading::Smooth && !mesh.vertexNormal.empty()
                                   ? mesh.vertexNormal[size_t(face[corner])]
                                   : faceNormal);
      }
    }
    b.count = int(list.positions.size()) - b.first;
    list.batches.push_back(b);
  }
  return list;
}

}  // namespace detail

Image renderHybrid(const ResultFile& mesh, const Scene& scene, const RenderOptions& o) {
  checkSize(o);
  if (o.backend != Backend::OsMesa)
    throw inputError("--mode hybrid", "--backend osmesa (the hybrid model is OpenGL-only)", "--backend software");
  if (o.radiance) throw inputError("--mode hybrid", "no --hdr (radiance is radiosity-only)", "--hdr");
  checkFaceSurfaces(mesh, scene, "--mode hybrid");
  if (scene.lights.empty()) throw inputError(scene.path, "a scene with lights for --mode hybrid", "none");
  const int w = o.width * o.ssaa, h = o.height * o.ssaa;
  glm::mat4 projection, view;
  viewProjection(mesh, effectiveCamera(mesh, o), w, h, &projection, &view);
  const bool stored = o.shade == Shading::Smooth && !o.exposure && mesh.exposure &&
                      !mesh.vertexColour.empty();
  detail::HybridDrawList list =
      detail::buildHybridDrawList(mesh, scene, o.shade, effectiveExposure(mesh, o), stored);
  std::vector<uint8_t> rgb;
  detail::renderOsMesaHybrid(list, scene, projection, view, w, h, o.shade, o.wireframe, rgb);
  Image image;
  image.width = o.width;
  image.height = o.height;
  image.rgb = downsampleBytes(rgb, o.width, o.height, o.ssaa);
  return image;
}

namespace {
/// Copies a tile (top row first) into the grid at cell `cell`.
void pasteTile(Image& grid, const Image& tile, int cell) {
  const int x0 = (cell % kLadderColumns) * tile.width, y0 = (cell / kLadderColumns) * tile.height;
  for (int y = 0; y < tile.height; ++y)
    std::copy_n(&tile.rgb[size_t(y) * tile.width * 3], size_t(tile.width) * 3,
                &grid.rgb[(size_t(y0 + y) * grid.width + x0) * 3]);
}

/// Ladder tiles drawn by the raster core: the wireframe (0) or hidden surfaces removed (1).
Image ladderSoftwareTile(const ResultFile& mesh, const Scene& scene, const RenderOptions& o,
                         bool wireframe) {
  const int w = o.width * o.ssaa, h = o.height * o.ssaa;
  const glm::mat4 mvp = viewProjection(mesh, effectiveCamera(mesh, o), w, h);
  raster::Target target(w, h, /*withItem=*/false, /*withColor=*/true);
  target.clearColor(glm::vec4(0, 0, 0, 1));
  std::vector<glm::vec4> clip;
  raster::transform(mvp, mesh.positions, clip);
  std::vector<uint32_t> indices;
  indices.reserve(mesh.faces.size() * 3);
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) indices.push_back(uint32_t(f[size_t(k)]));
  if (wireframe) {
    std::vector<uint32_t> edges;
    edges.reserve(indices.size() * 2);
    for (size_t t = 0; t < mesh.faces.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        edges.push_back(indices[3 * t + size_t(k)]);
        edges.push_back(indices[3 * t + size_t((k + 1) % 3)]);
      }
    raster::State state;
    state.depthTest = false;
    raster::drawLines(target, state, clip.data(), clip.size(), edges.data(), edges.size() / 2,
                      glm::vec4(glm::vec3(224 / 255.0f), 1.0f));
  } else {
    // De-indexed, flat: each triangle carries its surface's colour.
    std::vector<glm::vec4> faceClip, colours;
    faceClip.reserve(indices.size());
    colours.reserve(indices.size());
    for (size_t t = 0; t < mesh.faces.size(); ++t) {
      const int surface = mesh.faceSurface[t];
      const Material& m = scene.materials.at(size_t(scene.surfaces[size_t(surface)].material));
      const double peak = std::max({m.emission.x, m.emission.y, m.emission.z});
      // Brightness varied per surface (golden-ratio sequence in [0.45, 1]) so that neighbouring
      // surfaces of one material stay apart.
      const double shade = 0.45 + 0.55 * (1.0 - std::fmod(surface * 0.6180339887, 1.0));
      const glm::dvec3 linear = peak > 0 ? m.emission / peak : m.reflectance * shade;
      const glm::vec4 colour(float(srgbEncode(linear.x)), float(srgbEncode(linear.y)),
                             float(srgbEncode(linear.z)), 1.0f);
      for (int k = 0; k < 3; ++k) {
        faceClip.push_back(clip[indices[3 * t + size_t(k)]]);
        colours.push_back(colour);
      }
    }
    raster::State state;
    state.shade = raster::Shade::Flat;
    raster::drawTriangles(target, state, faceClip.data(), faceClip.size(), nullptr,
                          faceClip.size() / 3, nullptr, colours.data());
  }
  std::vector<uint8_t> rgb(size_t(w) * h * 3);
  for (size_t p = 0; p < target.color.size(); ++p)
    for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = toByte(target.color[p][c]);
  Image image;
  image.width = o.width;
  image.height = o.height;
  image.rgb = downsampleBytes(rgb, o.width, o.height, o.ssaa);
  return image;
}
}  // namespace

Image renderLadder(const ResultFile& mesh, const Scene& scene, const RenderOptions& options) {
  checkSize(options);
  if (options.backend != Backend::OsMesa)
    throw inputError("--ladder", "--backend osmesa (the local tiles are OpenGL-only)", "--backend software");
  if (options.radiance) throw inputError("--ladder", "no --hdr", "--hdr");
  if (options.wireframe) throw inputError("--ladder", "no --wireframe (the ladder has its own)", "--wireframe");
  if (int64_t(options.width) * kLadderColumns > raster::kMaxSize || options.height * 2 > raster::kMaxSize)
    throw inputError("--ladder", "a tile size whose grid fits " + std::to_string(raster::kMaxSize) + " pixels",
                     std::to_string(options.width) + "x" + std::to_string(options.height));
  checkFaceSurfaces(mesh, scene, "--ladder");
  RenderOptions o = options;
  o.camera = effectiveCamera(mesh, options);  // one view for every tile
  Image grid;
  grid.width = options.width * kLadderColumns;
  grid.height = options.height * ((kLadderTiles + kLadderColumns - 1) / kLadderColumns);
  grid.rgb.assign(size_t(grid.width) * grid.height * 3, 0);
  pasteTile(grid, ladderSoftwareTile(mesh, scene, o, /*wireframe=*/true), 0);
  pasteTile(grid, ladderSoftwareTile(mesh, scene, o, /*wireframe=*/false), 1);
  LocalScene local = prepareLocalScene(scene);
  RenderOptions lo = o;
  lo.exposure.reset();
  lo.shade = Shading::Flat;
  pasteTile(grid, renderLocal(local, lo), 2);
  lo.shade = Shading::Smooth;
  pasteTile(grid, renderLocal(local, lo), 3);
  for (Material& m : local.scene.materials)
    if (m.specular.x == 0 && m.specular.y == 0 && m.specular.z == 0) {
      m.specular = glm::dvec4(glm::dvec3(kLadderSpecular), 1.0);
      m.shininess = kLadderShininess;
    }
  pasteTile(grid, renderLocal(local, lo), 4);
  o.shade = Shading::Flat;
  pasteTile(grid, render(mesh, o), 5);
  o.shade = Shading::Smooth;
  pasteTile(grid, render(mesh, o), 6);
  return grid;
}

Image renderLocal(const LocalScene& local, const RenderOptions& o) {
  checkSize(o);
  if (o.backend != Backend::OsMesa)
    throw inputError("--mode local", "--backend osmesa (the local model is OpenGL-only)", "--backend software");
  if (o.exposure) throw inputError("--mode local", "no --exposure (lighting sets the brightness)", "--exposure");
  if (o.radiance) throw inputError("--mode local", "no --hdr (radiance is radiosity-only)", "--hdr");
  const int w = o.width * o.ssaa, h = o.height * o.ssaa;
  glm::mat4 projection, view;
  const ResultFile bounds = boundsOnly(local);
  viewProjection(bounds, effectiveCamera(bounds, o), w, h, &projection, &view);
  detail::LocalDrawList list = detail::buildLocalDrawList(local, o.shade);
  std::vector<uint8_t> rgb;
  detail::renderOsMesaLocal(list, local.scene, projection, view, w, h, o.shade, o.wireframe, rgb);
  Image image;
  image.width = o.width;
  image.height = o.height;
  image.rgb = downsampleBytes(rgb, o.width, o.height, o.ssaa);
  return image;
}

std::vector<uint32_t> renderFaceIds(const ResultFile& mesh, const RenderOptions& o) {
  raster::Target target(o.width, o.height, /*withItem=*/true, /*withColor=*/false);
  glm::mat4 mvp = viewProjection(mesh, effectiveCamera(mesh, o), o.width, o.height);
  std::vector<glm::vec4> clip;
  raster::transform(mvp, mesh.positions, clip);
  raster::State state;
  if (o.cullBack) state.cull = raster::Cull::Back;
  static_assert(sizeof(mesh.faces[0]) == 3 * sizeof(uint32_t), "faces are 3 packed indices");
  raster::drawTriangles(target, state, clip.data(), clip.size(),
                        reinterpret_cast<const uint32_t*>(mesh.faces.data()), mesh.faces.size());
  std::vector<uint32_t> out(target.item.size());
  for (int y = 0; y < o.height; ++y)
    std::copy_n(&target.item[size_t(o.height - 1 - y) * o.width], o.width, &out[size_t(y) * o.width]);
  return out;
}

void writePng(const std::string& path, const Image& image) {
  writeWithStb(path, [&](std::ostream& out) {
    return stbi_write_png_to_func(toStream, &out, image.width, image.height, 3, image.rgb.data(),
                                  image.width * 3);
  }, "PNG");
}

Image readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  if (!data) {
    const char* why = stbi_failure_reason();
    throw inputError(path, "a readable PNG image", why ? why : "an unreadable file");
  }
  Image image;
  image.width = w;
  image.height = h;
  image.rgb.assign(data, data + size_t(w) * h * 3);
  stbi_image_free(data);
  return image;
}

void writeHdr(const std::string& path, const Image& image) {
  if (image.radiance.size() != size_t(image.width) * image.height * 3)
    throw InternalError("writeHdr: the image has no radiance");
  writeWithStb(path, [&](std::ostream& out) {
    return stbi_write_hdr_to_func(toStream, &out, image.width, image.height, 3, image.radiance.data());
  }, "Radiance HDR");
}

}  // namespace rad::viewer
