#include "radiosity/result.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <glm/common.hpp>

#include "mesh/base/color.h"
#include "mesh/base/error.h"
#include "mesh/results/result_file.h"

namespace rad {

namespace {

/// The (luminance, area) of every element that does not emit, by luminance; `total` their area.
std::vector<std::pair<double, double>> sortedLuminances(const PatchMesh& m, const std::vector<glm::dvec3>& B,
                                                        double& total) {
  std::vector<std::pair<double, double>> lumArea;  // (luminance, area)
  total = 0;
  for (int e = 0; e < m.elementCount(); ++e) {
    if (luminance(m.emission(e)) > 0) continue;
    lumArea.emplace_back(luminance(B[e]), m.area(e));
    total += m.area(e);
  }
  std::sort(lumArea.begin(), lumArea.end());
  return lumArea;
}

/// The luminance below which kExposurePercentile of the area lies.
double percentileLuminance(const std::vector<std::pair<double, double>>& lumArea, double total) {
  double seen = 0, reference = 0;
  for (const auto& [lum, area] : lumArea) {
    seen += area;
    reference = lum;
    if (seen >= kExposurePercentile * total) break;
  }
  return reference;
}

}  // namespace

double autoExposure(const PatchMesh& m, const std::vector<glm::dvec3>& B) {
  double total = 0;
  const std::vector<std::pair<double, double>> lumArea = sortedLuminances(m, B, total);
  const double reference = percentileLuminance(lumArea, total);
  return reference > 0 ? kExposureTarget / reference : 1.0;
}

namespace {

/// The vertex indices of a face's three corners.
std::array<int, 3> cornerIndices(const PatchMesh& m, OpenMesh::FaceHandle f) {
  std::array<int, 3> corners;
  int k = 0;
  for (auto v : m.mesh.fv_range(f)) corners[size_t(k++)] = v.idx();
  return corners;
}

/// The vertices a face uses, in order: one that no face uses (left by the mesher where a seam
/// or refinement moved its faces away) has no normal and no light, and is not written.
std::vector<int> usedVertices(const PatchMesh& m) {
  std::vector<int> used;
  for (auto v : m.mesh.vertices())
    if (!m.mesh.is_isolated(v)) used.push_back(v.idx());
  return used;
}

/// The values of the used vertices (usedVertices), of values per vertex of the mesh.
template <class T>
std::vector<T> ofUsed(const std::vector<T>& perVertex, const std::vector<int>& used) {
  std::vector<T> out;
  out.reserve(used.size());
  for (int v : used) out.push_back(perVertex[size_t(v)]);
  return out;
}

/// The patch mesh's geometry as the result file holds it: the used vertices' positions and
/// normals, the elements' corners (indices among those) and their scene surfaces.
ResultFile resultGeometry(const PatchMesh& m, const std::vector<int>& used) {
  ResultFile r;
  std::vector<int> index(m.mesh.n_vertices(), -1);
  for (size_t k = 0; k < used.size(); ++k) {
    const auto v = m.mesh.vertex_handle(unsigned(used[k]));
    index[size_t(used[k])] = int(k);
    r.positions.push_back(glm::vec3(PatchMesh::toGlm(m.mesh.point(v))));
    r.vertexNormal.push_back(glm::vec3(PatchMesh::toGlm(m.mesh.normal(v))));
  }
  for (auto f : m.mesh.faces()) {
    std::array<int, 3> corners = cornerIndices(m, f);
    for (int& c : corners) c = index[size_t(c)];
    r.faces.push_back(corners);
  }
  for (int e = 0; e < m.elementCount(); ++e) r.faceSurface.push_back(m.surface(e));
  return r;
}

/// The display colour of each value at exposure K: sRGB(clamp(K·value)) per channel.
std::vector<std::array<uint8_t, 3>> displayColours(const std::vector<glm::dvec3>& values, double exposure) {
  std::vector<std::array<uint8_t, 3>> out;
  out.reserve(values.size());
  for (const auto& d : values)
    out.push_back({displayByte(d.x, exposure), displayByte(d.y, exposure), displayByte(d.z, exposure)});
  return out;
}

}  // namespace

void writeResult(const std::string& path, const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                 const glm::dvec3& ambient, double exposure, const Camera& camera,
                 const VertexDirect* direct) {
  const std::vector<int> used = usedVertices(mesh);
  ResultFile result = resultGeometry(mesh, used);
  result.vertexRadiosity = ofUsed(vertexRadiosity(mesh, B, direct), used);
  // The display colour adds ρ·ambient, reconstructed at the vertices like B.
  result.vertexColour = displayColours(
      ambient != glm::dvec3(0.0) ? ofUsed(shownVertexRadiosity(mesh, B, ambient, direct), used)
                                 : result.vertexRadiosity,
      exposure);
  result.faceRadiosity = B;
  result.camera = camera;
  result.exposure = exposure;
  writeResultFile(path, result);
}

void writeVertexResult(const std::string& path, const PatchMesh& mesh, const std::vector<glm::dvec3>& vertexB,
                       const std::vector<glm::dvec3>& B, double exposure, const Camera& camera) {
  const std::vector<int> used = usedVertices(mesh);
  ResultFile result = resultGeometry(mesh, used);
  result.vertexRadiosity = ofUsed(vertexB, used);
  result.vertexColour = displayColours(result.vertexRadiosity, exposure);
  result.faceRadiosity = B;
  result.camera = camera;
  result.exposure = exposure;
  writeResultFile(path, result);
}

/// Result positions are stored as float: points agree to this times the scene size.
constexpr double kSameGeometry = 1e-5;

namespace {

/// Whether the result's face e has the mesh's element e's corners, to within `tolerance`.
bool sameCorners(const ResultFile& result, const PatchMesh& mesh, int e, double tolerance) {
  const auto corners = mesh.corners(e);
  for (size_t k = 0; k < 3; ++k) {
    const glm::dvec3 p(result.positions[size_t(result.faces[size_t(e)][k])]);
    if (glm::length(p - corners[k]) > tolerance) return false;
  }
  return true;
}

}  // namespace

std::vector<glm::dvec3> readResultRadiosity(const std::string& path, const PatchMesh& mesh,
                                            double sceneSize) {
  const ResultFile result = readResultFile(path);
  const int n = mesh.elementCount();
  const std::string expected = "a result of the same scene and mesh settings";
  if (int(result.faces.size()) != n)
    throw inputError(path, expected + " (" + std::to_string(n) + " elements)",
                     std::to_string(result.faces.size()) + " faces");
  for (int e = 0; e < n; ++e)
    if (!sameCorners(result, mesh, e, kSameGeometry * sceneSize))
      throw inputError(path, expected, "element " + std::to_string(e) + " elsewhere");
  return result.faceRadiosity;
}

}  // namespace rad
