#pragma once
// The offscreen viewer (radview): draws a radiosity result mesh (DESIGN.md, "Result mesh") the
// way any OpenGL program would — vertex colours, Gouraud or flat shading, depth test — either
// through OSMesa's OpenGL or through the raster core (display/raster.h), to the same picture.
//
// Display colour: the sRGB encoding of clamp(K·B) (mesh/color.h displayByte), B being the
// vertex radiosity (smooth) or the element's own radiosity (flat), K the exposure.
// The radiance image (--hdr) is linear B/π per pixel.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rad::viewer {

/// gluLookAt / gluPerspective camera.
struct ViewCamera {
  glm::dvec3 eye{0.0}, target{0.0, 0.0, 1.0}, up{0.0, 1.0, 0.0};
  double fovYDeg = 45.0;
};

/// A radiosity result as read from its PLY file.
struct ResultMesh {
  std::string path;
  std::vector<glm::vec3> positions;
  std::vector<glm::dvec3> vertexRadiosity;
  std::vector<std::array<int, 3>> faces;
  std::vector<glm::dvec3> faceRadiosity;
  /// The file's display colours (red, green, blue), when present: sRGB(clamp(K·B)) plus, for
  /// a solve stopped before convergence, K·ρ·ambient (DESIGN.md, "Result mesh").
  std::vector<std::array<uint8_t, 3>> vertexColour;
  std::optional<ViewCamera> camera;  ///< from the `camera ...` header comment
  std::optional<double> exposure;    ///< from the `exposure K` header comment
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};
};

/// Reads a result PLY written by `radiosity solve`. Throws InputError naming the file and what
/// is missing (e.g. the radiosity properties of a plain `radiosity mesh` output).
ResultMesh loadResult(const std::string& path);

/// Parses "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F"; keys may come in any order and any subset
/// may be given, the others keep `base`'s values. Throws InputError("--camera: expected ...").
ViewCamera parseCamera(const std::string& text, const ViewCamera& base);

enum class Backend { OsMesa, Software };
enum class Shading { Smooth, Flat };

struct RenderOptions {
  int width = 512, height = 512;
  Shading shade = Shading::Smooth;
  Backend backend = Backend::OsMesa;
  std::optional<double> exposure;      ///< overrides the file's exposure
  std::optional<ViewCamera> camera;    ///< overrides the file's camera
  bool wireframe = false;              ///< OpenGL backend only
  int ssaa = 1;                        ///< supersampling factor per axis, box filter in linear light
  bool radiance = false;               ///< also produce the linear radiance image (B/π)
};

/// A rendered picture, TOP row first (as image files store it).
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;     ///< 3 bytes per pixel, sRGB display colour
  std::vector<float> radiance;  ///< 3 floats per pixel, linear B/π; empty unless asked for
};

/// The camera used for a render: options.camera, else the file's, else a default view along +z.
ViewCamera effectiveCamera(const ResultMesh& mesh, const RenderOptions& options);
/// The exposure used for a render: options.exposure, else the file's, else 1.
double effectiveExposure(const ResultMesh& mesh, const RenderOptions& options);
/// projection · view for a width × height picture (near and far planes fitted to the mesh's
/// bounding box), as loaded into OpenGL with glLoadMatrixf.
glm::mat4 viewProjection(const ResultMesh& mesh, const ViewCamera& camera, int width, int height,
                         glm::mat4* projection = nullptr, glm::mat4* view = nullptr);

/// Renders with the chosen backend. Throws InputError on bad options, std::runtime_error when
/// OpenGL (OSMesa) is unavailable.
Image render(const ResultMesh& mesh, const RenderOptions& options);

/// The face index seen at every pixel (software raster core, no supersampling), TOP row first;
/// raster::kNoItem where no face is seen. For tests and picking.
std::vector<uint32_t> renderFaceIds(const ResultMesh& mesh, const RenderOptions& options);

/// Writes the display colours as PNG, atomically. Throws InputError.
void writePng(const std::string& path, const Image& image);
/// Writes the radiance as Radiance HDR (RGBE), atomically. Throws InputError.
void writeHdr(const std::string& path, const Image& image);

namespace detail {
/// Per-vertex colours of the triangles as drawn (de-indexed: 3 vertices per face), shared by
/// both backends: positions, display colour in [0, 1] and radiance B/π.
struct DrawList {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec4> display;
  std::vector<glm::vec4> radiance;
};
/// storedColours: take the file's vertex colours (smooth shading at the file's exposure).
DrawList buildDrawList(const ResultMesh& mesh, Shading shade, double exposure,
                       bool storedColours = false);
/// OpenGL rendering through OSMesa at width × height: bytes (RGB, BOTTOM row first) and, when
/// radiance != nullptr, linear radiance (RGB floats, bottom row first).
void renderOsMesa(const DrawList& list, const glm::mat4& projection, const glm::mat4& view,
                  int width, int height, Shading shade, bool wireframe, std::vector<uint8_t>& rgb,
                  std::vector<float>* radiance);
}  // namespace detail

}  // namespace rad::viewer
