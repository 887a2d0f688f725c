#pragma once
// The result file (DESIGN.md, "Result mesh"), the one place that knows its format: a binary
// little-endian PLY whose vertices carry position, normal, display colour and linear radiosity,
// whose faces carry their scene surface and the element's own radiosity, with the camera and the
// exposure in header comments. `radiosity solve` writes it; the viewer and `solve --fixed-point`
// read it, every property and comment checked (finite positions, radiosity >= 0, a usable
// camera), so that nothing downstream reads past a buffer or draws NaN. Needs the PLY reader
// and writer only.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/scene/scene.h"

namespace rad {

/// A result as the file holds it. The optional parts (normals, colours, surfaces, camera,
/// exposure) are empty when the file has none; the writer leaves out what is empty.
struct ResultFile {
  std::vector<glm::vec3> positions;                  ///< vertex x y z
  std::vector<glm::vec3> vertexNormal;               ///< vertex nx ny nz
  /// Vertex red green blue: sRGB(clamp(K·B)) plus, for a solve stopped before convergence,
  /// K·ρ·ambient.
  std::vector<std::array<uint8_t, 3>> vertexColour;
  std::vector<glm::dvec3> vertexRadiosity;           ///< vertex radiosity_r/g/b (no ambient)
  std::vector<std::array<int, 3>> faces;             ///< vertex_indices
  std::vector<int> faceSurface;                      ///< face `surface`: scene surface index
  std::vector<glm::dvec3> faceRadiosity;             ///< face radiosity_r/g/b
  std::optional<Camera> camera;                      ///< `comment camera eye ... fov_y_deg F`
  std::optional<double> exposure;                    ///< `comment exposure K`

  // Set by readResultFile.
  std::string path;                                  ///< the file read
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};         ///< bounding box of the positions
};

/// Writes the result file atomically (temporary file, then rename); numbers as float, colours as
/// bytes, with 9 significant digits in the comments. Throws InputError when it cannot be written.
void writeResultFile(const std::string& path, const ResultFile& result);

/// Reads a result file written by `radiosity solve`. Throws InputError naming the file, the
/// vertex or face and what was expected and found (e.g. the radiosity properties a plain
/// `radiosity mesh` output lacks).
ResultFile readResultFile(const std::string& path);

}  // namespace rad
