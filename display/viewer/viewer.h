#pragma once
// The offscreen viewer (radview): draws a radiosity result mesh (DESIGN.md, "Result mesh") the
// way any OpenGL program would — vertex colours, Gouraud or flat shading, depth test — either
// through OSMesa's OpenGL or through the raster core (display/raster/raster.h), to the same picture.
//
// Display colour: the sRGB encoding of clamp(K·B) (mesh/base/color.h displayByte), B being the
// vertex radiosity (smooth) or the element's own radiosity (flat), K the exposure.
// The radiance image (--hdr) is linear B/π per pixel.
//
// Where each part lives: render_options.cpp (--camera, the effective camera and exposure, the
// matrices), radiosity_render.cpp (radiosity mode, both backends, the software wireframe),
// local_render.cpp (local lighting), hybrid_render.cpp, ladder.cpp (the realism ladder),
// osmesa_render.cpp (every OpenGL call), downsample.cpp (supersampling), image_file.cpp (PNG and
// HDR files); the result file itself is mesh/results/result_file.h.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "display/raster/raster.h"
#include "mesh/patch_mesh.h"
#include "mesh/results/result_file.h"
#include "mesh/scene/scene.h"

namespace rad::viewer {

/// Parses "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F"; keys may come in any order and any subset
/// may be given, the others keep `base`'s values. Throws InputError("--camera: expected ...").
Camera parseCamera(const std::string& text, const Camera& base);

enum class Backend { OsMesa, Software };
enum class Shading { Smooth, Flat };

struct RenderOptions {
  int width = 512, height = 512;
  Shading shade = Shading::Smooth;
  Backend backend = Backend::OsMesa;
  std::optional<double> exposure;      ///< overrides the file's exposure
  std::optional<Camera> camera;        ///< overrides the file's camera
  bool wireframe = false;              ///< overlay the element edges (both backends)
  int ssaa = 1;                        ///< supersampling factor per axis, box filter in linear light
  bool radiance = false;               ///< also produce the linear radiance image (B/π)
  /// Radiosity mode (render, renderFaceIds): remove back faces, those clockwise in window
  /// coordinates (OpenGL: glEnable(GL_CULL_FACE), glCullFace(GL_BACK), glFrontFace(GL_CCW);
  /// raster core: State::cull = Cull::Back). Wireframe edges of culled triangles are not drawn.
  bool cullBack = false;
};

/// A rendered picture, TOP row first (as image files store it).
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;     ///< 3 bytes per pixel, sRGB display colour
  std::vector<float> radiance;  ///< 3 floats per pixel, linear B/π; empty unless asked for
};

/// The camera used for a render: options.camera, else the file's, else one chosen from the
/// result's triangles as for a scene without a camera (mesh/results/default_camera.h).
Camera effectiveCamera(const ResultFile& mesh, const RenderOptions& options);
/// The exposure used for a render: options.exposure, else the file's, else 1.
double effectiveExposure(const ResultFile& mesh, const RenderOptions& options);
/// projection · view for a width × height picture (near and far planes fitted to the mesh's
/// bounding box), as loaded into OpenGL with glLoadMatrixf.
glm::mat4 viewProjection(const ResultFile& mesh, const Camera& camera, int width, int height,
                         glm::mat4* projection = nullptr, glm::mat4* view = nullptr);

/// Renders with the chosen backend. Throws InputError on bad options, std::runtime_error when
/// OpenGL (OSMesa) is unavailable.
Image render(const ResultFile& mesh, const RenderOptions& options);

/// The face index seen at every pixel (software raster core, no supersampling), TOP row first;
/// raster::kNoItem where no face is seen. For tests and picking.
std::vector<uint32_t> renderFaceIds(const ResultFile& mesh, const RenderOptions& options);

/// Writes the display colours as PNG, atomically. Throws InputError.
void writePng(const std::string& path, const Image& image);
/// Reads an 8-bit PNG (as written by writePng; other channel counts are converted to RGB) into
/// an Image without radiance. Throws InputError naming the file.
Image readPng(const std::string& path);
/// Writes the radiance as Radiance HDR (RGBE), atomically. Throws InputError.
void writeHdr(const std::string& path, const Image& image);

// ---- Local-illumination mode (radview --mode local) -------------------------------------------
// The scene lit by OpenGL's fixed-function model through OSMesa: the scene's `lights` (at most
// 8), `light_model` and `fog`, one glMaterial per surface (ambient, diffuse, specular,
// shininess), vertex normals of the patch mesh (smooth) or face normals with GL_FLAT (flat).
// Emissive surfaces get GL_EMISSION = E / max(E.r, E.g, E.b): the emission colour normalised to
// full brightness, so lamps show at their hue without any exposure rule. OSMesa only.

/// A scene meshed for the local model. `scene` may be edited after preparation (materials,
/// lights, fog, camera) as long as the geometry stays: the mesh depends on geometry only.
struct LocalScene {
  Scene scene;
  PatchMesh mesh;
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};
};

/// Meshes the scene with its own settings (resolveSettings(scene, {}).mesh()). Throws
/// InputError "<scene>: expected a scene with lights for --mode local, found none" without
/// lights.
LocalScene prepareLocalScene(Scene scene);
/// loadScene + prepareLocalScene.
LocalScene loadLocalScene(const std::string& path);
/// The camera of a local render: options.camera, else the scene's, else defaultCamera of the
/// patch mesh's bounding box.
Camera effectiveCamera(const LocalScene& local, const RenderOptions& options);
/// Renders the local model (OSMesa). options.backend must be OsMesa; exposure and radiance are
/// not used (InputError when set). Throws std::runtime_error when OSMesa is unavailable.
Image renderLocal(const LocalScene& local, const RenderOptions& options);

// ---- Hybrid mode (radview --mode hybrid) --------------------------------------------------------
// Radiosity as the diffuse part plus the scene's lights' specular highlights, through OSMesa:
// lighting on, material ambient and diffuse zero, glColorMaterial(GL_EMISSION) fed with the
// display colours radiosity mode draws (so emission = radiosity colour), material specular and
// shininess from the scene per surface (the face property `surface`), the scene's lights and
// light model, GL_LIGHT_MODEL_COLOR_CONTROL = GL_SEPARATE_SPECULAR_COLOR. No fog. Normals: the
// file's vertex normals (smooth; face normals when the file has none) or face normals (flat).

/// Renders the hybrid picture. The mesh must carry face `surface` indices valid in `scene`
/// (InputError otherwise); options.backend must be OsMesa and radiance off (InputError).
Image renderHybrid(const ResultFile& mesh, const Scene& scene, const RenderOptions& options);

// ---- The realism ladder (radview --ladder) ------------------------------------------------------
// One picture of the same view (the result's camera, or options.camera) in kLadderTiles tiles of
// options.width × options.height, kLadderColumns per row, row-major from the top left (the last
// cell of the second row stays black):
//   0 wireframe (every element edge of the result, light grey on black, no hidden-line removal),
//   1 hidden surfaces removed (one constant colour per surface: sRGB of its reflectance times a
//     per-surface brightness in [0.45, 1] (golden-ratio sequence over the surface index, so that
//     surfaces of one material stay apart), or of its emission normalised to full brightness for
//     emitters; depth test),
//   2 flat local, 3 smooth local (renderLocal of the scene, meshed with its own settings),
//   4 smooth local with specular (materials without a specular colour get kLadderSpecular and
//     shininess kLadderShininess),
//   5 radiosity flat (each element's own value), 6 radiosity Gouraud (as render()).
// Tiles 0 and 1 are drawn by the raster core, the others through OSMesa. options.backend must be
// OsMesa, wireframe and radiance off (InputError); exposure and ssaa apply as usual.
constexpr int kLadderTiles = 7;
constexpr int kLadderColumns = 4;
constexpr double kLadderSpecular = 0.4;
constexpr double kLadderShininess = 30;
Image renderLadder(const ResultFile& mesh, const Scene& scene, const RenderOptions& options);

namespace detail {
/// Display byte (all three channels) of wireframe edges, in both backends.
constexpr uint8_t kWireByte = 16;
/// Constant part of the depth bias of software wireframe lines toward the viewer (window depth).
constexpr float kWireDepthBias = 1e-5f;
/// Draws the edges of every triangle (indices 3 per triangle, or null = de-indexed: triangle t
/// is clip[3t..3t+2]) into `target` in the wireframe colour, depth-tested (LESS) with a bias
/// toward the viewer of the triangle's largest window-depth slope per pixel plus
/// kWireDepthBias: the mirror of glPolygonOffset(1, 1) on the fill pass of the OpenGL path.
void drawSoftwareWireframe(raster::Target& target, const std::vector<glm::vec4>& clip,
                           const std::vector<uint32_t>* triangles);

/// The local model's geometry, de-indexed (3 vertices per triangle), grouped by surface.
struct LocalBatch {
  int first = 0, count = 0;  ///< vertex range
  glm::vec4 ambient{0.0f}, diffuse{0.0f}, specular{0.0f}, emission{0.0f};
  float shininess = 0;
};
struct LocalDrawList {
  std::vector<glm::vec3> positions, normals;
  std::vector<LocalBatch> batches;
};
LocalDrawList buildLocalDrawList(const LocalScene& local, Shading shade);
/// The hybrid model's geometry: de-indexed, grouped by surface (batches carry only the
/// specular colour and shininess), with the display colour per vertex.
struct HybridDrawList {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec4> colours;
  std::vector<LocalBatch> batches;
};
HybridDrawList buildHybridDrawList(const ResultFile& mesh, const Scene& scene, Shading shade,
                                   double exposure, bool storedColours);
/// Radiosity emission plus fixed-function specular through OSMesa: bytes (RGB, BOTTOM row first).
void renderOsMesaHybrid(const HybridDrawList& list, const Scene& scene, const glm::mat4& projection,
                        const glm::mat4& view, int width, int height, Shading shade,
                        bool wireframe, std::vector<uint8_t>& rgb);
/// Fixed-function lighting through OSMesa: bytes (RGB, BOTTOM row first).
void renderOsMesaLocal(const LocalDrawList& list, const Scene& scene, const glm::mat4& projection,
                       const glm::mat4& view, int width, int height, Shading shade, bool wireframe,
                       std::vector<uint8_t>& rgb);

/// Per-vertex colours of the triangles as drawn (de-indexed: 3 vertices per face), shared by
/// both backends: positions, display colour in [0, 1] and radiance B/π.
struct DrawList {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec4> display;
  std::vector<glm::vec4> radiance;
};
/// storedColours: take the file's vertex colours (smooth shading at the file's exposure).
DrawList buildDrawList(const ResultFile& mesh, Shading shade, double exposure,
                       bool storedColours = false);
/// OpenGL rendering through OSMesa at width × height: bytes (RGB, BOTTOM row first) and, when
/// radiance != nullptr, linear radiance (RGB floats, bottom row first).
void renderOsMesa(const DrawList& list, const glm::mat4& projection, const glm::mat4& view,
                  int width, int height, Shading shade, bool wireframe, std::vector<uint8_t>& rgb,
                  std::vector<float>* radiance, bool cullBack = false);
/// Whether the triangle (clip-space vertices) is front-facing, counter-clockwise in window
/// coordinates: the sign of det(x, y, w) of its vertices, valid for any w (also for triangles
/// crossing the eye plane, whose clipped parts keep that orientation).
bool frontFacing(const glm::vec4& a, const glm::vec4& b, const glm::vec4& c);
}  // namespace detail

}  // namespace rad::viewer
