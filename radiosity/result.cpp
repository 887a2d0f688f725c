#include "radiosity/result.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <glm/common.hpp>

#include "mesh/color.h"
#include "mesh/error.h"
#include "mesh/mesh_export.h"
#include "mesh/ply_reader.h"

namespace rad {

double autoExposure(const PatchMesh& m, const std::vector<glm::dvec3>& B) {
  std::vector<std::pair<double, double>> lumArea;  // (luminance, area)
  double total = 0;
  for (int e = 0; e < m.elementCount(); ++e) {
    if (luminance(m.emission(e)) > 0) continue;
    lumArea.emplace_back(luminance(B[e]), m.area(e));
    total += m.area(e);
  }
  std::sort(lumArea.begin(), lumArea.end());
  double seen = 0, reference = 0;
  for (const auto& [lum, area] : lumArea) {
    seen += area;
    reference = lum;
    if (seen >= kExposurePercentile * total) break;
  }
  return reference > 0 ? kExposureTarget / reference : 1.0;
}

Camera defaultCamera(const Scene& scene) {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const auto& s : scene.surfaces)
    for (const auto& p : s.polygons)
      for (const auto& q : p.outer) lo = glm::min(lo, q), hi = glm::max(hi, q);
  Camera c;
  c.fovYDeg = 45;
  c.target = (lo + hi) * 0.5;
  double radius = glm::length(hi - lo) * 0.5;
  double distance = radius / std::sin(glm::radians(c.fovYDeg) * 0.5);
  c.eye = c.target - glm::dvec3(0, 0, distance);
  c.up = glm::dvec3(0, 1, 0);
  return c;
}

void writeResult(const std::string& path, const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                 const glm::dvec3& ambient, double exposure, const Camera& camera,
                 const VertexDirect* direct) {
  std::vector<glm::dvec3> vertexB = vertexRadiosity(mesh, B, direct);
  // The display colour adds ρ·ambient, reconstructed at the vertices like B.
  const std::vector<glm::dvec3> display =
      ambient != glm::dvec3(0.0) ? shownVertexRadiosity(mesh, B, ambient, direct) : vertexB;
  PlyMesh ply = toPly(mesh);
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "camera eye %.9g %.9g %.9g target %.9g %.9g %.9g up %.9g %.9g %.9g fov_y_deg %.9g",
                camera.eye.x, camera.eye.y, camera.eye.z, camera.target.x, camera.target.y,
                camera.target.z, camera.up.x, camera.up.y, camera.up.z, camera.fovYDeg);
  ply.comments.push_back(buf);
  std::snprintf(buf, sizeof buf, "exposure %.9g", exposure);
  ply.comments.push_back(buf);
  const char* colours[] = {"red", "green", "blue"};
  const char* channels[] = {"radiosity_r", "radiosity_g", "radiosity_b"};
  for (int k = 0; k < 3; ++k) {
    PlyColumn c{colours[k], PlyColumn::Type::UChar, {}};
    for (const auto& d : display) c.values.push_back(displayByte(d[k], exposure));
    ply.vertex.push_back(std::move(c));
  }
  for (int k = 0; k < 3; ++k) {
    PlyColumn c{channels[k], PlyColumn::Type::Float, {}};
    for (const auto& b : vertexB) c.values.push_back(b[k]);
    ply.vertex.push_back(std::move(c));
  }
  for (int k = 0; k < 3; ++k) {
    PlyColumn c{channels[k], PlyColumn::Type::Float, {}};
    for (const auto& b : B) c.values.push_back(b[k]);
    ply.face.push_back(std::move(c));
  }
  writePly(path, ply);
}

/// Result positions are stored as float: points agree to this times the scene size.
constexpr double kSameGeometry = 1e-5;

std::vector<glm::dvec3> readResultRadiosity(const std::string& path, const PatchMesh& mesh,
                                            double sceneSize) {
  PlyMesh ply = readPly(path);
  const int n = mesh.elementCount();
  const std::string expected = "a result of the same scene and mesh settings";
  if (int(ply.faces.size()) != n)
    throw inputError(path, expected + " (" + std::to_string(n) + " elements)",
                     std::to_string(ply.faces.size()) + " faces");
  const PlyColumn* channel[3];
  std::string missing;
  const char* names[] = {"radiosity_r", "radiosity_g", "radiosity_b"};
  for (int k = 0; k < 3; ++k)
    if (!(channel[k] = findColumn(ply.face, names[k]))) missing += std::string(missing.empty() ? "" : ", ") + names[k];
  const PlyColumn* xyz[3] = {findColumn(ply.vertex, "x"), findColumn(ply.vertex, "y"),
                             findColumn(ply.vertex, "z")};
  if (!xyz[0] || !xyz[1] || !xyz[2]) missing += std::string(missing.empty() ? "" : ", ") + "vertex x y z";
  if (!missing.empty()) throw inputError(path, "face radiosity_r/g/b and vertex x y z", "no " + missing);
  std::vector<glm::dvec3> B(n);
  for (int e = 0; e < n; ++e) {
    auto corners = mesh.corners(e);
    for (int k = 0; k < 3; ++k) {
      int v = ply.faces[e][k];
      glm::dvec3 p(xyz[0]->values[v], xyz[1]->values[v], xyz[2]->values[v]);
      if (glm::length(p - corners[k]) > kSameGeometry * sceneSize)
        throw inputError(path, expected, "element " + std::to_string(e) + " elsewhere");
    }
    B[e] = {channel[0]->values[e], channel[1]->values[e], channel[2]->values[e]};
  }
  return B;
}

}  // namespace rad
