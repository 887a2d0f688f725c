// The realism ladder (radview --ladder): one view of the result drawn seven ways, from the
// wireframe to radiosity with Gouraud shading, as tiles of one picture.
#include <algorithm>
#include <cmath>

#include "display/viewer/viewer_internal.h"
#include "mesh/base/color.h"
#include "mesh/base/error.h"

namespace rad::viewer {
namespace {

/// Display value of the wireframe tile's lines (light grey on black).
constexpr float kLadderWireGrey = 224 / 255.0f;

/// Copies a tile (top row first) into the grid at cell `cell`.
void pasteTile(Image& grid, const Image& tile, int cell) {
  const int x0 = (cell % kLadderColumns) * tile.width, y0 = (cell / kLadderColumns) * tile.height;
  for (int y = 0; y < tile.height; ++y)
    std::copy_n(&tile.rgb[size_t(y) * tile.width * 3], size_t(tile.width) * 3,
                &grid.rgb[(size_t(y0 + y) * grid.width + x0) * 3]);
}

/// Appends the face's three edges as pairs of vertex indices.
template <class Face>
void appendFaceEdges(std::vector<uint32_t>& edges, const Face& f) {
  for (size_t k = 0; k < 3; ++k) {
    edges.push_back(uint32_t(f[k]));
    edges.push_back(uint32_t(f[(k + 1) % 3]));
  }
}

/// Every face's three edges as pairs of vertex indices.
std::vector<uint32_t> faceEdges(const ResultFile& mesh) {
  std::vector<uint32_t> edges;
  edges.reserve(mesh.faces.size() * 6);
  for (const auto& f : mesh.faces) appendFaceEdges(edges, f);
  return edges;
}

/// Tile 0: every element edge, no hidden-line removal.
void drawWireframeTile(raster::Target& target, const std::vector<glm::vec4>& clip, const ResultFile& mesh) {
  const std::vector<uint32_t> edges = faceEdges(mesh);
  raster::State state;
  state.depthTest = false;
  raster::drawLines(target, state, clip.data(), clip.size(), edges.data(), edges.size() / 2,
                    glm::vec4(glm::vec3(kLadderWireGrey), 1.0f));
}

/// The constant colour of a surface in tile 1: sRGB of its emission normalised to full
/// brightness for emitters, else of its reflectance times a brightness varied per surface
/// (golden-ratio sequence in [0.45, 1]) so that neighbouring surfaces of one material stay apart.
glm::vec4 surfaceColour(const Scene& scene, int surface) {
  const Material& m = scene.materials.at(size_t(scene.surfaces[size_t(surface)].material));
  const double peak = internal::peakEmission(m);
  const double shade = 0.45 + 0.55 * (1.0 - std::fmod(surface * 0.6180339887, 1.0));
  const glm::dvec3 linear = peak > 0 ? m.emission / peak : m.reflectance * shade;
  return glm::vec4(float(srgbEncode(linear.x)), float(srgbEncode(linear.y)), float(srgbEncode(linear.z)), 1.0f);
}

/// De-indexed triangles (3 clip-space corners each) and the colour of each corner.
struct ColouredCorners {
  std::vector<glm::vec4> clip, colours;
};

/// Appends face t's three corners, each in `colour`.
void appendFaceCorners(ColouredCorners& corners, const std::vector<glm::vec4>& clip, const ResultFile& mesh,
                       size_t t, const glm::vec4& colour) {
  for (size_t k = 0; k < 3; ++k) {
    corners.clip.push_back(clip[size_t(mesh.faces[t][k])]);
    corners.colours.push_back(colour);
  }
}

/// Every face de-indexed, each in its surface's colour.
ColouredCorners surfaceCorners(const std::vector<glm::vec4>& clip, const ResultFile& mesh,
                               const Scene& scene) {
  ColouredCorners corners;
  corners.clip.reserve(mesh.faces.size() * 3);
  corners.colours.reserve(mesh.faces.size() * 3);
  for (size_t t = 0; t < mesh.faces.size(); ++t)
    appendFaceCorners(corners, clip, mesh, t, surfaceColour(scene, mesh.faceSurface[t]));
  return corners;
}

/// Tile 1: hidden surfaces removed, de-indexed and flat, each triangle in its surface's colour.
void drawSurfacesTile(raster::Target& target, const std::vector<glm::vec4>& clip, const ResultFile& mesh,
                      const Scene& scene) {
  const ColouredCorners corners = surfaceCorners(clip, mesh, scene);
  raster::State state;
  state.shade = raster::Shade::Flat;
  raster::drawTriangles(target, state, corners.clip.data(), corners.clip.size(), nullptr,
                        corners.clip.size() / 3, nullptr, corners.colours.data());
}

/// Ladder tiles drawn by the raster core: the wireframe (0) or hidden surfaces removed (1).
Image softwareTile(const ResultFile& mesh, const Scene& scene, const RenderOptions& o, bool wireframe) {
  const internal::FrameView v = internal::frameView(mesh, effectiveCamera(mesh, o), o);
  raster::Target target(v.width, v.height, /*withItem=*/false, /*withColor=*/true);
  target.clearColor(glm::vec4(0, 0, 0, 1));
  const std::vector<glm::vec4> clip = internal::clipCoordinates(v.mvp, mesh.positions);
  if (wireframe) drawWireframeTile(target, clip, mesh);
  else drawSurfacesTile(target, clip, mesh, scene);
  return internal::imageOf(internal::targetBytes(target), o);
}

/// Throws unless the grid of tiles fits the largest picture.
void checkGridFits(const RenderOptions& options) {
  if (int64_t(options.width) * kLadderColumns > raster::kMaxSize || options.height * 2 > raster::kMaxSize)
    throw inputError("--ladder", "a tile size whose grid fits " + std::to_string(raster::kMaxSize) + " pixels",
                     std::to_string(options.width) + "x" + std::to_string(options.height));
}

/// Refuses the flags the ladder cannot honour: the software backend, --hdr and --wireframe.
void checkLadderFlags(const RenderOptions& options) {
  if (options.backend != Backend::OsMesa)
    throw inputError("--ladder", "--backend osmesa (the local tiles are OpenGL-only)", "--backend software");
  if (options.radiance) throw inputError("--ladder", "no --hdr", "--hdr");
  if (options.wireframe) throw inputError("--ladder", "no --wireframe (the ladder has its own)", "--wireframe");
}

/// The ladder's own limits on the options: OSMesa, no --hdr or --wireframe, a grid that fits.
void checkLadderOptions(const RenderOptions& options) {
  internal::checkSize(options);
  checkLadderFlags(options);
  checkGridFits(options);
}

/// The ladder's limits on the options, and a result whose faces name surfaces of the scene.
void checkLadderInputs(const ResultFile& mesh, const Scene& scene, const RenderOptions& options) {
  checkLadderOptions(options);
  internal::checkFaceSurfaces(mesh, scene, "--ladder");
}

/// Gives the materials without a specular colour kLadderSpecular and kLadderShininess.
void addDefaultSpecular(std::vector<Material>& materials) {
  for (Material& m : materials)
    if (m.specular.x == 0 && m.specular.y == 0 && m.specular.z == 0) {
      m.specular = glm::dvec4(glm::dvec3(kLadderSpecular), 1.0);
      m.shininess = kLadderShininess;
    }
}

/// The options with shading `shade`.
RenderOptions withShade(RenderOptions o, Shading shade) {
  o.shade = shade;
  return o;
}

/// Tiles 0 and 1, drawn by the raster core: the wireframe and hidden surfaces removed.
void pasteSoftwareTiles(Image& grid, const ResultFile& mesh, const Scene& scene, const RenderOptions& o) {
  pasteTile(grid, softwareTile(mesh, scene, o, /*wireframe=*/true), 0);
  pasteTile(grid, softwareTile(mesh, scene, o, /*wireframe=*/false), 1);
}

/// Tiles 2 to 4: the scene lit by the local model, flat, smooth, and smooth with specular
/// (kLadderSpecular and kLadderShininess where a material has no specular colour).
void pasteLocalTiles(Image& grid, const Scene& scene, const RenderOptions& o) {
  LocalScene local = prepareLocalScene(scene);
  RenderOptions lo = o;
  lo.exposure.reset();
  pasteTile(grid, renderLocal(local, withShade(lo, Shading::Flat)), 2);
  pasteTile(grid, renderLocal(local, withShade(lo, Shading::Smooth)), 3);
  addDefaultSpecular(local.scene.materials);
  pasteTile(grid, renderLocal(local, withShade(lo, Shading::Smooth)), 4);
}

/// The black grid of the ladder's tiles, kLadderColumns wide.
Image blankGrid(const RenderOptions& options) {
  Image grid;
  grid.width = options.width * kLadderColumns;
  grid.height = options.height * ((kLadderTiles + kLadderColumns - 1) / kLadderColumns);
  grid.rgb.assign(size_t(grid.width) * grid.height * 3, 0);
  return grid;
}

/// Tiles 5 and 6: the radiosity result, flat and Gouraud.
void pasteRadiosityTiles(Image& grid, const ResultFile& mesh, const RenderOptions& o) {
  pasteTile(grid, render(mesh, withShade(o, Shading::Flat)), 5);
  pasteTile(grid, render(mesh, withShade(o, Shading::Smooth)), 6);
}

}  // namespace

Image renderLadder(const ResultFile& mesh, const Scene& scene, const RenderOptions& options) {
  checkLadderInputs(mesh, scene, options);
  RenderOptions o = options;
  o.camera = effectiveCamera(mesh, options);  // one view for every tile
  Image grid = blankGrid(options);
  pasteSoftwareTiles(grid, mesh, scene, o);
  pasteLocalTiles(grid, scene, o);
  pasteRadiosityTiles(grid, mesh, o);
  return grid;
}

}  // namespace rad::viewer
