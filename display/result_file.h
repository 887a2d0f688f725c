#pragma once
// The result file (DESIGN.md, "Result mesh") as the viewer reads it: every property and comment
// checked (finite positions, radiosity >= 0, a usable camera), so that nothing downstream reads
// past a buffer or draws NaN. Needs the mesh part's PLY reader only.
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
  /// Vertex normals (nx, ny, nz), when present (used by --mode hybrid).
  std::vector<glm::vec3> vertexNormal;
  /// Each face's scene surface index (the face property `surface`), when present.
  std::vector<int> faceSurface;
  std::optional<ViewCamera> camera;  ///< from the `camera ...` header comment
  std::optional<double> exposure;    ///< from the `exposure K` header comment
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};
};

/// Reads a result PLY written by `radiosity solve`. Throws InputError naming the file and what
/// is missing (e.g. the radiosity properties of a plain `radiosity mesh` output).
ResultMesh loadResult(const std::string& path);

/// Checks a camera for finite values and a usable frame; `where` names the source. Throws
/// InputError.
void checkCamera(const ViewCamera& c, const std::string& where);

}  // namespace rad::viewer
