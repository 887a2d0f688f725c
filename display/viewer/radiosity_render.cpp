// Radiosity mode: the result's display colours (or radiance B/π) per vertex, drawn through
// OSMesa's OpenGL or the raster core to the same picture, with the software wireframe that
// mirrors OpenGL's.
#include <algorithm>
#include <array>
#include <cmath>

#include "display/viewer/viewer_internal.h"
#include "mesh/base/color.h"

namespace rad::viewer {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The display colour of radiosity b at exposure K, as OpenGL takes it: bytes scaled to [0, 1].
glm::vec4 displayColour(const glm::dvec3& b, double exposure) {
  return glm::vec4(displayByte(b.x, exposure) / 255.0f, displayByte(b.y, exposure) / 255.0f,
                   displayByte(b.z, exposure) / 255.0f, 1.0f);
}

/// A stored display colour (bytes) scaled to [0, 1].
glm::vec4 storedColour(const std::array<uint8_t, 3>& c) {
  return glm::vec4(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f);
}

/// A clip-space point in window coordinates (pixels in a W x H picture, depth in [0, 1]).
glm::dvec3 windowPoint(const glm::dvec4& c, double W, double H) {
  return glm::dvec3((c.x / c.w + 1) * 0.5 * W, (c.y / c.w + 1) * 0.5 * H, (c.z / c.w + 1) * 0.5);
}

/// The largest window-depth slope per pixel of the plane through three window points (0 when
/// the triangle is edge-on).
double depthSlope(const glm::dvec3 w[3]) {
  const glm::dvec3 n = glm::cross(w[1] - w[0], w[2] - w[0]);
  return std::abs(n.z) > 1e-12 ? std::max(std::abs(n.x / n.z), std::abs(n.y / n.z)) : 0.0;
}

/// The window points `w` of the triangle with vertices v in a W x H picture; false (and `w`
/// unfinished) when a vertex is not in front of the eye.
bool windowPoints(const std::vector<glm::vec4>& clip, const uint32_t v[3], double W, double H, glm::dvec3 w[3]) {
  for (int k = 0; k < 3; ++k) {
    const glm::dvec4 c(clip[v[k]]);
    if (c.w <= 0) return false;
    w[k] = windowPoint(c, W, H);
  }
  return true;
}

/// The window-depth bias of a triangle's wireframe: its largest window-depth slope per pixel
/// (its depth plane, when all three vertices are in front of the eye) plus kWireDepthBias, as
/// glPolygonOffset(1, 1) pushes the fill back in OpenGL.
float wireDepthBias(const std::vector<glm::vec4>& clip, const uint32_t v[3], double W, double H) {
  glm::dvec3 w[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
  const double slope = windowPoints(clip, v, W, H, w) ? depthSlope(w) : 0.0;
  return float(slope + detail::kWireDepthBias);
}

/// The vertex indices of triangle t: from `triangles`, or 3t..3t+2 when that is null.
std::array<uint32_t, 3> triangleCorners(const std::vector<uint32_t>* triangles, size_t t) {
  if (triangles) return {(*triangles)[3 * t], (*triangles)[3 * t + 1], (*triangles)[3 * t + 2]};
  return {uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2)};
}

/// Draws the three edges of the triangle with vertices v in `colour`, depth-tested with its
/// wireframe bias toward the viewer.
void drawTriangleEdges(raster::Target& target, const std::vector<glm::vec4>& clip, const uint32_t v[3],
                       const glm::vec4& colour) {
  const raster::State state;
  const uint32_t edges[6] = {v[0], v[1], v[1], v[2], v[2], v[0]};
  raster::drawLines(target, state, clip.data(), clip.size(), edges, 3, colour,
                    wireDepthBias(clip, v, target.width, target.height));
}

/// The vertex indices of the front-facing triangles of a de-indexed list (3 vertices each).
std::vector<uint32_t> frontTriangles(const std::vector<glm::vec4>& clip) {
  std::vector<uint32_t> front;
  for (uint32_t t = 0; 3 * size_t(t) + 2 < clip.size(); ++t)
    if (detail::frontFacing(clip[3 * t], clip[3 * t + 1], clip[3 * t + 2]))
      front.insert(front.end(), {3 * t, 3 * t + 1, 3 * t + 2});
  return front;
}

/// The RGB floats of the target's colour buffer.
std::vector<float> colourFloats(const raster::Target& target) {
  return internal::targetRgb<float>(target, [](float v) { return v; });
}

/// Draws the de-indexed triangles (3 clip-space vertices each) in their per-vertex colours.
void drawColoured(raster::Target& target, const raster::State& state, const std::vector<glm::vec4>& clip,
                  const std::vector<glm::vec4>& colours) {
  const size_t n = clip.size();
  raster::drawTriangles(target, state, clip.data(), n, nullptr, n / 3, nullptr, colours.data());
}

/// The raster core's radiance picture of the draw list (RGB floats, bottom-up) into `target`.
std::vector<float> softwareRadiance(raster::Target& target, const raster::State& state,
                                    const std::vector<glm::vec4>& clip, const detail::DrawList& list) {
  target.clear();
  drawColoured(target, state, clip, list.radiance);
  return colourFloats(target);
}

/// The wireframe over the picture; with back-face culling, only the front faces' edges.
void drawWireframeOver(raster::Target& target, const std::vector<glm::vec4>& clip, bool cullBack) {
  if (!cullBack) return detail::drawSoftwareWireframe(target, clip, nullptr);
  // As OpenGL culls before GL_LINE rasterisation: only the front faces' edges.
  const std::vector<uint32_t> front = frontTriangles(clip);
  detail::drawSoftwareWireframe(target, clip, &front);
}

/// The raster core's state culling back faces or none.
raster::State cullingState(bool cullBack) {
  raster::State state;
  if (cullBack) state.cull = raster::Cull::Back;
  return state;
}

/// The raster core's state for the radiosity picture: flat or smooth, culling back faces or none.
raster::State softwareState(Shading shade, bool cullBack) {
  raster::State state = cullingState(cullBack);
  state.shade = shade == Shading::Flat ? raster::Shade::Flat : raster::Shade::Smooth;
  return state;
}

/// The raster core's picture of the draw list: bytes and optionally radiance, bottom-up.
void renderSoftware(const detail::DrawList& list, const internal::FrameView& v, const RenderOptions& o,
                    std::vector<uint8_t>& rgb, std::vector<float>* radiance) {
  raster::Target target(v.width, v.height, /*withItem=*/false, /*withColor=*/true);
  const raster::State state = softwareState(o.shade, o.cullBack);
  const std::vector<glm::vec4> clip = internal::clipCoordinates(v.mvp, list.positions);
  drawColoured(target, state, clip, list.display);
  if (o.wireframe) drawWireframeOver(target, clip, o.cullBack);
  rgb = internal::targetBytes(target);
  if (radiance) *radiance = softwareRadiance(target, state, clip, list);
}

/// Draws the mesh's faces (vertices `clip`) into the item buffer, each as its face index.
void drawFaceIds(raster::Target& target, const std::vector<glm::vec4>& clip, const ResultFile& mesh,
                 bool cullBack) {
  static_assert(sizeof(mesh.faces[0]) == 3 * sizeof(uint32_t), "faces are 3 packed indices");
  raster::drawTriangles(target, cullingState(cullBack), clip.data(), clip.size(),
                        reinterpret_cast<const uint32_t*>(mesh.faces.data()), mesh.faces.size());
}

/// Draws the list in view `v` on the backend `o` names: the display bytes into rgb and, when
/// o.radiance, the radiance into `radiance` (both bottom row first).
void drawOnBackend(const detail::DrawList& list, const internal::FrameView& v, const RenderOptions& o,
                   std::vector<uint8_t>& rgb, std::vector<float>& radiance) {
  std::vector<float>* radianceOut = o.radiance ? &radiance : nullptr;
  if (o.backend == Backend::Software) renderSoftware(list, v, o, rgb, radianceOut);
  else detail::renderOsMesa(list, v.projection, v.view, v.width, v.height, o.shade, o.wireframe, rgb,
                            radianceOut, o.cullBack);
}

/// The display colour of vertex v showing radiosity b: the file's stored colour, or b's at
/// `exposure`.
glm::vec4 cornerDisplay(const ResultFile& mesh, int v, const glm::dvec3& b, double exposure, bool storedColours) {
  return storedColours ? storedColour(mesh.vertexColour[v]) : displayColour(b, exposure);
}

/// Room for n vertices in each of the list's arrays.
void reserveVertices(detail::DrawList& list, size_t n) {
  list.positions.reserve(n);
  list.display.reserve(n);
  list.radiance.reserve(n);
}

/// Appends face f's three corners: position, display colour and radiance B/π of the face's
/// own radiosity (flat) or its vertex's.
void appendFace(detail::DrawList& list, const ResultFile& mesh, size_t f, Shading shade, double exposure,
                bool storedColours) {
  for (int corner = 0; corner < 3; ++corner) {
    const int v = mesh.faces[f][corner];
    const glm::dvec3& b = shade == Shading::Flat ? mesh.faceRadiosity[f] : mesh.vertexRadiosity[v];
    list.positions.push_back(mesh.positions[v]);
    list.display.push_back(cornerDisplay(mesh, v, b, exposure, storedColours));
    list.radiance.push_back(glm::vec4(glm::dvec3(b / kPi), 1.0));
  }
}

/// The draw list of a render with options `o`: its shading and exposure, the stored colours
/// when they show.
detail::DrawList drawListFor(const ResultFile& mesh, const RenderOptions& o) {
  return detail::buildDrawList(mesh, o.shade, effectiveExposure(mesh, o), internal::showsStoredColours(mesh, o));
}

/// The picture at the asked size from the drawn bytes and, when asked, the radiance.
Image pictureOf(const std::vector<uint8_t>& rgb, const std::vector<float>& radiance, const RenderOptions& o) {
  Image image = internal::imageOf(rgb, o);
  if (o.radiance) image.radiance = internal::downsampleFloats(radiance, o.width, o.height, o.ssaa);
  return image;
}

}  // namespace

namespace detail {

bool frontFacing(const glm::vec4& a, const glm::vec4& b, const glm::vec4& c) {
  const glm::dvec3 p(a.x, a.y, a.w), q(b.x, b.y, b.w), r(c.x, c.y, c.w);
  return glm::dot(p, glm::cross(q, r)) > 0;
}

void drawSoftwareWireframe(raster::Target& target, const std::vector<glm::vec4>& clip,
                           const std::vector<uint32_t>* triangles) {
  const size_t triangleCount = triangles ? triangles->size() / 3 : clip.size() / 3;
  const glm::vec4 colour(glm::vec3(kWireByte / 255.0f), 1.0f);
  for (size_t t = 0; t < triangleCount; ++t)
    drawTriangleEdges(target, clip, triangleCorners(triangles, t).data(), colour);
}

DrawList buildDrawList(const ResultFile& mesh, Shading shade, double exposure, bool storedColours) {
  DrawList list;
  reserveVertices(list, mesh.faces.size() * 3);
  for (size_t f = 0; f < mesh.faces.size(); ++f) appendFace(list, mesh, f, shade, exposure, storedColours);
  return list;
}

}  // namespace detail

namespace internal {

std::vector<glm::vec4> clipCoordinates(const glm::mat4& mvp, const std::vector<glm::vec3>& points) {
  std::vector<glm::vec4> clip;
  raster::transform(mvp, points, clip);
  return clip;
}

bool showsStoredColours(const ResultFile& mesh, const RenderOptions& o) {
  // Gouraud at the file's own exposure shows the file's colours, which carry the ambient term of
  // an unconverged solve; anything else is computed from the radiosities.
  return o.shade == Shading::Smooth && !o.exposure && mesh.exposure && !mesh.vertexColour.empty();
}

}  // namespace internal

Image render(const ResultFile& mesh, const RenderOptions& o) {
  internal::checkSize(o);
  const internal::FrameView v = internal::frameView(mesh, effectiveCamera(mesh, o), o);
  std::vector<uint8_t> rgb;
  std::vector<float> radiance;
  drawOnBackend(drawListFor(mesh, o), v, o, rgb, radiance);
  return pictureOf(rgb, radiance, o);
}

std::vector<uint32_t> renderFaceIds(const ResultFile& mesh, const RenderOptions& o) {
  raster::Target target(o.width, o.height, /*withItem=*/true, /*withColor=*/false);
  const glm::mat4 mvp = viewProjection(mesh, effectiveCamera(mesh, o), o.width, o.height);
  drawFaceIds(target, internal::clipCoordinates(mvp, mesh.positions), mesh, o.cullBack);
  return internal::topRowFirst(target.item, target.width, target.height, 1);
}

}  // namespace rad::viewer
