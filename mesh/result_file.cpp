#include "mesh/result_file.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include <glm/common.hpp>

#include "mesh/camera.h"
#include "mesh/error.h"
#include "mesh/ply_reader.h"
#include "mesh/ply_writer.h"

namespace rad {
namespace {

/// The radiosity properties of the result file, per vertex and per face.
const char* const kChannels[3] = {"radiosity_r", "radiosity_g", "radiosity_b"};
const char* const kPosition[3] = {"x", "y", "z"};
const char* const kNormal[3] = {"nx", "ny", "nz"};
const char* const kColour[3] = {"red", "green", "blue"};

/// The shortest text of a number, as the messages show it.
std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// ---- Writing ----------------------------------------------------------------------------------

/// Appends three columns `names` of `type`, one value per element of `values` and channel.
template <class Vec3>
void addColumns(std::vector<PlyColumn>& columns, const char* const names[3], PlyColumn::Type type,
                const std::vector<Vec3>& values) {
  for (int k = 0; k < 3; ++k) {
    PlyColumn c{names[k], type, {}};
    c.values.reserve(values.size());
    for (const auto& v : values) c.values.push_back(double(v[k]));
    columns.push_back(std::move(c));
  }
}

/// The header comments: the camera, then the exposure.
std::vector<std::string> comments(const ResultFile& r) {
  std::vector<std::string> out;
  char buf[512];
  if (r.camera) {
    const Camera& c = *r.camera;
    std::snprintf(buf, sizeof buf,
                  "camera eye %.9g %.9g %.9g target %.9g %.9g %.9g up %.9g %.9g %.9g fov_y_deg %.9g",
                  c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                  c.up.z, c.fovYDeg);
    out.push_back(buf);
  }
  if (r.exposure) {
    std::snprintf(buf, sizeof buf, "exposure %.9g", *r.exposure);
    out.push_back(buf);
  }
  return out;
}

/// Vertex columns in the contract's order: x y z, nx ny nz, red green blue, radiosity_r/g/b.
std::vector<PlyColumn> vertexColumns(const ResultFile& r) {
  std::vector<PlyColumn> columns;
  addColumns(columns, kPosition, PlyColumn::Type::Float, r.positions);
  if (!r.vertexNormal.empty()) addColumns(columns, kNormal, PlyColumn::Type::Float, r.vertexNormal);
  if (!r.vertexColour.empty()) addColumns(columns, kColour, PlyColumn::Type::UChar, r.vertexColour);
  addColumns(columns, kChannels, PlyColumn::Type::Float, r.vertexRadiosity);
  return columns;
}

/// Face columns after vertex_indices: surface, radiosity_r/g/b.
std::vector<PlyColumn> faceColumns(const ResultFile& r) {
  std::vector<PlyColumn> columns;
  if (!r.faceSurface.empty())
    columns.push_back({"surface", PlyColumn::Type::Int, {r.faceSurface.begin(), r.faceSurface.end()}});
  addColumns(columns, kChannels, PlyColumn::Type::Float, r.faceRadiosity);
  return columns;
}

// ---- Reading ----------------------------------------------------------------------------------

/// The columns every result has: vertex x y z and radiosity, face radiosity.
struct RequiredColumns {
  const PlyColumn *position[3], *vertexB[3], *faceB[3];
};

/// Finds the required columns; throws InputError listing every missing one.
RequiredColumns requiredColumns(const PlyMesh& ply, const std::string& path) {
  std::vector<std::string> missing;
  auto need = [&](const std::vector<PlyColumn>& cols, const char* name, const char* element) {
    const PlyColumn* c = findColumn(cols, name);
    if (!c) missing.push_back(std::string(element) + " " + name);
    return c;
  };
  RequiredColumns r;
  for (int k = 0; k < 3; ++k) r.position[k] = need(ply.vertex, kPosition[k], "vertex");
  for (int k = 0; k < 3; ++k) r.vertexB[k] = need(ply.vertex, kChannels[k], "vertex");
  for (int k = 0; k < 3; ++k) r.faceB[k] = need(ply.face, kChannels[k], "face");
  if (missing.empty()) return r;
  std::string list;
  for (size_t i = 0; i < missing.size(); ++i) list += (i ? ", " : "") + missing[i];
  throw inputError(path,
                   "a radiosity result (vertex and face properties radiosity_r, radiosity_g, "
                   "radiosity_b, as `radiosity solve` writes)",
                   "a PLY without " + list);
}

/// The three columns `names` when all are there, else nullptr in each.
std::array<const PlyColumn*, 3> optionalColumns(const std::vector<PlyColumn>& columns,
                                                const char* const names[3]) {
  std::array<const PlyColumn*, 3> c{};
  for (int k = 0; k < 3; ++k) c[size_t(k)] = findColumn(columns, names[k]);
  if (!(c[0] && c[1] && c[2])) c = {};
  return c;
}

/// Row i of three columns.
glm::dvec3 row(const PlyColumn* const c[3], size_t i) {
  return {c[0]->values[i], c[1]->values[i], c[2]->values[i]};
}

/// Throws unless b is a finite radiosity >= 0 in each channel; `where` names the vertex or face.
void checkRadiosity(const glm::dvec3& b, int k, const std::string& where) {
  if (!(std::isfinite(b[k]) && b[k] >= 0))
    throw inputError(where + ": " + kChannels[k], "a finite radiosity >= 0", fmt(b[k]));
}

/// Positions (finite), vertex radiosities (finite, >= 0) and their bounding box.
void readVertices(const RequiredColumns& cols, ResultFile& r) {
  const size_t nv = cols.position[0]->values.size();
  r.positions.resize(nv);
  r.vertexRadiosity.resize(nv);
  r.boundsMin = glm::dvec3(std::numeric_limits<double>::infinity());
  r.boundsMax = -r.boundsMin;
  for (size_t i = 0; i < nv; ++i) {
    const glm::dvec3 p = row(cols.position, i), b = row(cols.vertexB, i);
    const std::string where = r.path + ": vertex " + std::to_string(i);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p[k])) throw inputError(where, "finite coordinates", "a non-finite one");
      checkRadiosity(b, k, where);
    }
    r.positions[i] = glm::vec3(p);
    r.vertexRadiosity[i] = b;
    r.boundsMin = glm::min(r.boundsMin, p);
    r.boundsMax = glm::max(r.boundsMax, p);
  }
}

/// The display colours, when the file has them, each from 0 to 255.
void readColours(const PlyMesh& ply, ResultFile& r) {
  const auto rgb = optionalColumns(ply.vertex, kColour);
  if (!rgb[0]) return;
  r.vertexColour.resize(r.positions.size());
  for (size_t i = 0; i < r.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = rgb[size_t(k)]->values[i];
      if (!(v >= 0 && v <= 255))
        throw inputError(r.path + ": vertex " + std::to_string(i) + ": " + rgb[size_t(k)]->name,
                         "a colour from 0 to 255", fmt(v));
      r.vertexColour[i][size_t(k)] = uint8_t(v);
    }
}

/// The vertex normals, when the file has them.
void readNormals(const PlyMesh& ply, ResultFile& r) {
  const auto n = optionalColumns(ply.vertex, kNormal);
  if (!n[0]) return;
  r.vertexNormal.resize(r.positions.size());
  for (size_t i = 0; i < r.positions.size(); ++i)
    r.vertexNormal[i] = glm::vec3(row(n.data(), i));
}

/// The faces' surface indices, when the file has them: whole numbers >= 0 within int.
void readSurfaces(const PlyMesh& ply, ResultFile& r) {
  const PlyColumn* surface = findColumn(ply.face, "surface");
  if (!surface) return;
  r.faceSurface.resize(r.faces.size());
  for (size_t f = 0; f < r.faces.size(); ++f) {
    const double v = surface->values[f];
    if (!(v >= 0 && v < 2147483647.0 && v == std::floor(v)))
      throw inputError(r.path + ": face " + std::to_string(f) + ": surface", "a surface index >= 0", fmt(v));
    r.faceSurface[f] = int(v);
  }
}

/// The elements' own radiosities (finite, >= 0).
void readFaceRadiosity(const RequiredColumns& cols, ResultFile& r) {
  r.faceRadiosity.resize(r.faces.size());
  for (size_t f = 0; f < r.faces.size(); ++f) {
    const glm::dvec3 b = row(cols.faceB, f);
    for (int k = 0; k < 3; ++k) checkRadiosity(b, k, r.path + ": face " + std::to_string(f));
    r.faceRadiosity[f] = b;
  }
}

/// Parses "camera eye X Y Z target X Y Z up X Y Z fov_y_deg F"; false when the text does not
/// follow the pattern.
bool parseCameraComment(const std::string& text, Camera& c) {
  std::istringstream s(text);
  std::string camera, eye, target, up, fov;
  if (!(s >> camera >> eye >> c.eye.x >> c.eye.y >> c.eye.z >> target >> c.target.x >> c.target.y >>
        c.target.z >> up >> c.up.x >> c.up.y >> c.up.z >> fov >> c.fovYDeg))
    return false;
  return camera == "camera" && eye == "eye" && target == "target" && up == "up" &&
         fov == "fov_y_deg";
}

/// The camera comment: the pattern, then a usable camera.
Camera readCamera(const std::string& comment, const std::string& path) {
  Camera c;
  if (!parseCameraComment(comment, c))
    throw inputError(path + ": comment camera", "eye X Y Z target X Y Z up X Y Z fov_y_deg F",
                     "'" + comment + "'");
  checkCamera(c, path + ": comment camera");
  return c;
}

/// The exposure comment: a finite K > 0.
double readExposure(const std::string& comment, const std::string& path) {
  std::istringstream s(comment.substr(8));
  double k;
  if (!(s >> k) || !std::isfinite(k) || k <= 0)
    throw inputError(path + ": comment exposure", "a finite exposure > 0", "'" + comment + "'");
  return k;
}

/// The camera and exposure comments; other comments are left alone.
void readComments(const PlyMesh& ply, ResultFile& r) {
  for (const auto& comment : ply.comments) {
    if (comment.rfind("camera", 0) == 0) r.camera = readCamera(comment, r.path);
    else if (comment.rfind("exposure", 0) == 0) r.exposure = readExposure(comment, r.path);
  }
}

/// Each optional part is empty or has one value per vertex or face.
void checkSizes(const ResultFile& r) {
  const size_t nv = r.positions.size(), nf = r.faces.size();
  RAD_CHECK_EQ(r.vertexRadiosity.size(), nv);
  RAD_CHECK(r.vertexNormal.empty() || r.vertexNormal.size() == nv);
  RAD_CHECK(r.vertexColour.empty() || r.vertexColour.size() == nv);
  RAD_CHECK_EQ(r.faceRadiosity.size(), nf);
  RAD_CHECK(r.faceSurface.empty() || r.faceSurface.size() == nf);
}

}  // namespace

void writeResultFile(const std::string& path, const ResultFile& result) {
  checkSizes(result);
  PlyMesh ply;
  ply.comments = comments(result);
  ply.vertex = vertexColumns(result);
  ply.faces = result.faces;
  ply.face = faceColumns(result);
  writePly(path, ply);
}

ResultFile readResultFile(const std::string& path) {
  const PlyMesh ply = readPly(path);
  ResultFile r;
  r.path = path;
  const RequiredColumns cols = requiredColumns(ply, path);
  if (ply.faces.empty()) throw inputError(path, "a mesh with faces", "none");
  readVertices(cols, r);
  readColours(ply, r);
  readNormals(ply, r);
  r.faces = ply.faces;
  readSurfaces(ply, r);
  readFaceRadiosity(cols, r);
  readComments(ply, r);
  return r;
}

}  // namespace rad
