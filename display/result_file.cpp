#include "display/result_file.h"

#include <cmath>
#include <sstream>

#include "mesh/error.h"
#include "mesh/ply_reader.h"

namespace rad::viewer {
namespace {

/// The radiosity properties of the result mesh, per vertex and per face.
const char* const kChannels[3] = {"radiosity_r", "radiosity_g", "radiosity_b"};

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// Parses "<key> X Y Z ..." comments; false when the text does not follow the pattern.
bool parseCameraComment(const std::string& text, ViewCamera& c) {
  std::istringstream s(text);
  std::string camera, eye, target, up, fov;
  if (!(s >> camera >> eye >> c.eye.x >> c.eye.y >> c.eye.z >> target >> c.target.x >> c.target.y >>
        c.target.z >> up >> c.up.x >> c.up.y >> c.up.z >> fov >> c.fovYDeg))
    return false;
  return camera == "camera" && eye == "eye" && target == "target" && up == "up" &&
         fov == "fov_y_deg";
}

}  // namespace

void checkCamera(const ViewCamera& c, const std::string& where) {
  for (double v : {c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                   c.up.z, c.fovYDeg})
    if (!std::isfinite(v)) throw inputError(where, "finite camera values", "a non-finite value");
  if (!(c.fovYDeg > 0 && c.fovYDeg < 180))
    throw inputError(where, "a vertical field of view in (0, 180) degrees", fmt(c.fovYDeg));
  glm::dvec3 forward = c.target - c.eye;
  if (glm::length(forward) == 0) throw inputError(where, "an eye distinct from the target", "the same point");
  if (glm::length(glm::cross(forward, c.up)) <= 1e-12 * glm::length(forward) * glm::length(c.up))
    throw inputError(where, "an up vector not parallel to the view direction", "a parallel one");
}


ResultMesh loadResult(const std::string& path) {
  PlyMesh ply = readPly(path);
  ResultMesh m;
  m.path = path;
  std::vector<std::string> missing;
  auto need = [&](const std::vector<PlyColumn>& cols, const char* name, const char* element) {
    const PlyColumn* c = findColumn(cols, name);
    if (!c) missing.push_back(std::string(element) + " " + name);
    return c;
  };
  const PlyColumn* xyz[3] = {need(ply.vertex, "x", "vertex"), need(ply.vertex, "y", "vertex"),
                             need(ply.vertex, "z", "vertex")};
  const PlyColumn *vb[3], *fb[3];
  for (int k = 0; k < 3; ++k) vb[k] = need(ply.vertex, kChannels[k], "vertex");
  for (int k = 0; k < 3; ++k) fb[k] = need(ply.face, kChannels[k], "face");
  if (!missing.empty()) {
    std::string list;
    for (size_t i = 0; i < missing.size(); ++i) list += (i ? ", " : "") + missing[i];
    throw inputError(path,
                     "a radiosity result (vertex and face properties radiosity_r, radiosity_g, "
                     "radiosity_b, as `radiosity solve` writes)",
                     "a PLY without " + list);
  }
  if (ply.faces.empty()) throw inputError(path, "a mesh with faces", "none");
  const size_t nv = xyz[0]->values.size();
  m.positions.resize(nv);
  m.vertexRadiosity.resize(nv);
  m.boundsMin = glm::dvec3(std::numeric_limits<double>::infinity());
  m.boundsMax = -m.boundsMin;
  for (size_t i = 0; i < nv; ++i) {
    glm::dvec3 p(xyz[0]->values[i], xyz[1]->values[i], xyz[2]->values[i]);
    glm::dvec3 b(vb[0]->values[i], vb[1]->values[i], vb[2]->values[i]);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p[k]))
        throw inputError(path + ": vertex " + std::to_string(i), "finite coordinates", "a non-finite one");
      if (!(std::isfinite(b[k]) && b[k] >= 0))
        throw inputError(path + ": vertex " + std::to_string(i) + ": " + kChannels[k],
                         "a finite radiosity >= 0", fmt(b[k]));
    }
    m.positions[i] = glm::vec3(p);
    m.vertexRadiosity[i] = b;
    m.boundsMin = glm::min(m.boundsMin, p);
    m.boundsMax = glm::max(m.boundsMax, p);
  }
  const PlyColumn* rgb[3] = {findColumn(ply.vertex, "red"), findColumn(ply.vertex, "green"),
                             findColumn(ply.vertex, "blue")};
  if (rgb[0] && rgb[1] && rgb[2]) {
    m.vertexColour.resize(nv);
    for (size_t i = 0; i < nv; ++i)
      for (int k = 0; k < 3; ++k) {
        const double v = rgb[k]->values[i];
        if (!(v >= 0 && v <= 255))
          throw inputError(path + ": vertex " + std::to_string(i) + ": " + rgb[k]->name, "a colour from 0 to 255", fmt(v));
        m.vertexColour[i][k] = uint8_t(v);
      }
  }
  const PlyColumn* nrm[3] = {findColumn(ply.vertex, "nx"), findColumn(ply.vertex, "ny"),
                             findColumn(ply.vertex, "nz")};
  if (nrm[0] && nrm[1] && nrm[2]) {
    m.vertexNormal.resize(nv);
    for (size_t i = 0; i < nv; ++i)
      m.vertexNormal[i] = glm::vec3(nrm[0]->values[i], nrm[1]->values[i], nrm[2]->values[i]);
  }
  m.faces = ply.faces;
  if (const PlyColumn* surface = findColumn(ply.face, "surface")) {
    m.faceSurface.resize(m.faces.size());
    for (size_t f = 0; f < m.faces.size(); ++f) {
      const double v = surface->values[f];
      if (!(v >= 0 && v < 2147483647.0 && v == std::floor(v)))
        throw inputError(path + ": face " + std::to_string(f) + ": surface", "a surface index >= 0", fmt(v));
      m.faceSurface[f] = int(v);
    }
  }
  m.faceRadiosity.resize(m.faces.size());
  for (size_t f = 0; f < m.faces.size(); ++f) {
    glm::dvec3 b(fb[0]->values[f], fb[1]->values[f], fb[2]->values[f]);
    for (int k = 0; k < 3; ++k)
      if (!(std::isfinite(b[k]) && b[k] >= 0))
        throw inputError(path + ": face " + std::to_string(f) + ": " + kChannels[k],
                         "a finite radiosity >= 0", fmt(b[k]));
    m.faceRadiosity[f] = b;
  }
  for (const auto& comment : ply.comments) {
    if (comment.rfind("camera", 0) == 0) {
      ViewCamera c;
      if (!parseCameraComment(comment, c))
        throw inputError(path + ": comment camera", "eye X Y Z target X Y Z up X Y Z fov_y_deg F",
                         "'" + comment + "'");
      checkCamera(c, path + ": comment camera");
      m.camera = c;
    } else if (comment.rfind("exposure", 0) == 0) {
      std::istringstream s(comment.substr(8));
      double k;
      if (!(s >> k) || !std::isfinite(k) || k <= 0)
        throw inputError(path + ": comment exposure", "a finite exposure > 0", "'" + comment + "'");
      m.exposure = k;
    }
  }
  return m;
}

}  // namespace rad::viewer
