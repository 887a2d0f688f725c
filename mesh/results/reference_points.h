#pragma once
// The reference file (CSV): radiosity at surface points computed by an independent method (the
// path tracer of radiosity/pathtrace), with its standard error. Written by `radiosity reference`,
// read by `radiosity solve --reference` and `radiosity convergence` to measure the true error.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace rad {

/// One point of a reference: where, facing which way, on which surface, and its radiosity.
struct ReferencePoint {
  glm::dvec3 position{0.0}, normal{0.0};  ///< scene units; unit normal of the lit side
  std::string surface;                    ///< the scene surface's name
  std::string tag;                        ///< "area", "edge" or the user's own
  glm::dvec3 B{0.0};                      ///< radiosity per channel
  glm::dvec3 standardError{0.0};          ///< of B, per channel
  long paths = 0;                         ///< paths that estimated it
};

/// A reference file: its header lines (`key: value`, without the leading "# ") and points.
struct ReferenceFile {
  std::vector<std::string> header;
  std::vector<ReferencePoint> points;
};

/// The column names, in order.
constexpr const char* kReferenceColumns =
    "x,y,z,nx,ny,nz,surface,tag,B_r,B_g,B_b,se_r,se_g,se_b,paths";

/// Writes the file atomically (temporary file, then rename): `# ` header lines, the column
/// names, one line per point with 17 significant digits.
void writeReferenceFile(const std::string& path, const ReferenceFile& file);

/// Reads a reference file; throws InputError naming the file, the line and what was expected
/// (every number finite, B and its standard error non-negative, normals of unit length).
ReferenceFile readReferenceFile(const std::string& path);

}  // namespace rad
