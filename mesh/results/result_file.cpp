#include "mesh/results/result_file.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include <glm/common.hpp>

#include "mesh/base/error.h"
#include "mesh/base/number_text.h"
#include "mesh/base/ply_reader.h"
#include "mesh/base/ply_writer.h"
#include "mesh/scene/camera.h"

namespace rad {
namespace {

/// The radiosity properties of the result file, per vertex and per face.
const char* const kChannels[3] = {"radiosity_r", "radiosity_g", "radiosity_b"};
const char* const kPosition[3] = {"x", "y", "z"};
const char* const kNormal[3] = {"nx", "ny", "nz"};
const char* const kColour[3] = {"red", "green", "blue"};

// ---- Writing ----------------------------------------------------------------------------------

/// Channel k of `values` as a column `name` of `type`.
template <class Vec3>
PlyColumn channelColumn(const char* name, PlyColumn::Type type, const std::vector<Vec3>& values, int k) {
  PlyColumn c{name, type, {}};
  c.values.reserve(values.size());
  for (const auto& v : values) c.values.push_back(double(v[k]));
  return c;
}

/// Appends three columns `names` of `type`, one value per element of `values` and channel.
template <class Vec3>
void addColumns(std::vector<PlyColumn>& columns, const char* const names[3], PlyColumn::Type type,
                const std::vector<Vec3>& values) {
  for (int k = 0; k < 3; ++k) columns.push_back(channelColumn(names[k], type, values, k));
}

/// The camera comment: "camera eye X Y Z target X Y Z up X Y Z fov_y_deg F".
std::string cameraComment(const Camera& c) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "camera eye %.9g %.9g %.9g target %.9g %.9g %.9g up %.9g %.9g %.9g fov_y_deg %.9g",
                c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                c.up.z, c.fovYDeg);
  return buf;
}

/// The exposure comment: "exposure K".
std::string exposureComment(double exposure) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "exposure %.9g", exposure);
  return buf;
}

/// The header comments: the camera, then the exposure.
std::vector<std::string> comments(const ResultFile& r) {
  std::vector<std::string> out;
  if (r.camera) out.push_back(cameraComment(*r.camera));
  if (r.exposure) out.push_back(exposureComment(*r.exposure));
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

/// Looks up columns, noting each missing one as "<element> <name>".
struct ColumnLookup {
  std::vector<std::string> missing;

  /// The three columns `names` of `element` into `out` (null where missing).
  void three(const PlyColumn* out[3], const std::vector<PlyColumn>& columns, const char* const names[3],
             const char* element) {
    for (int k = 0; k < 3; ++k) out[k] = one(columns, names[k], element);
  }

  /// The column `name` of `element`, or null (noted).
  const PlyColumn* one(const std::vector<PlyColumn>& columns, const char* name, const char* element) {
    const PlyColumn* c = findColumn(columns, name);
    if (!c) missing.push_back(std::string(element) + " " + name);
    return c;
  }
};

/// The words joined by ", ".
std::string commaList(const std::vector<std::string>& words) {
  std::string list;
  for (size_t i = 0; i < words.size(); ++i) list += (i ? ", " : "") + words[i];
  return list;
}

/// The error for a PLY without the `missing` columns of a result.
InputError notAResult(const std::string& path, const std::vector<std::string>& missing) {
  return inputError(path,
                    "a radiosity result (vertex and face properties radiosity_r, radiosity_g, "
                    "radiosity_b, as `radiosity solve` writes)",
                    "a PLY without " + commaList(missing));
}

/// Finds the required columns; throws InputError listing every missing one.
RequiredColumns requiredColumns(const PlyMesh& ply, const std::string& path) {
  ColumnLookup lookup;
  RequiredColumns r;
  lookup.three(r.position, ply.vertex, kPosition, "vertex");
  lookup.three(r.vertexB, ply.vertex, kChannels, "vertex");
  lookup.three(r.faceB, ply.face, kChannels, "face");
  if (lookup.missing.empty()) return r;
  throw notAResult(path, lookup.missing);
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
    throw inputError(where + ": " + kChannels[k], "a finite radiosity >= 0", shortNumberText(b[k]));
}

/// Throws unless the position p is finite and b a finite radiosity >= 0, channel by channel.
void checkVertex(const glm::dvec3& p, const glm::dvec3& b, const std::string& where) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(p[k])) throw inputError(where, "finite coordinates", "a non-finite one");
    checkRadiosity(b, k, where);
  }
}

/// Vertex i's position and radiosity, checked and stored; the bounding box grown to it.
void readVertex(const RequiredColumns& cols, size_t i, ResultFile& r) {
  const glm::dvec3 p = row(cols.position, i), b = row(cols.vertexB, i);
  checkVertex(p, b, r.path + ": vertex " + std::to_string(i));
  r.positions[i] = glm::vec3(p);
  r.vertexRadiosity[i] = b;
  r.boundsMin = glm::min(r.boundsMin, p);
  r.boundsMax = glm::max(r.boundsMax, p);
}

/// Positions (finite), vertex radiosities (finite, >= 0) and their bounding box.
void readVertices(const RequiredColumns& cols, ResultFile& r) {
  const size_t nv = cols.position[0]->values.size();
  r.positions.resize(nv);
  r.vertexRadiosity.resize(nv);
  r.boundsMin = glm::dvec3(std::numeric_limits<double>::infinity());
  r.boundsMax = -r.boundsMin;
  for (size_t i = 0; i < nv; ++i) readVertex(cols, i, r);
}

/// Vertex i's value in colour column c, from 0 to 255.
uint8_t colourByte(const PlyColumn& c, size_t i, const std::string& path) {
  const double v = c.values[i];
  if (!(v >= 0 && v <= 255))
    throw inputError(path + ": vertex " + std::to_string(i) + ": " + c.name, "a colour from 0 to 255",
                     shortNumberText(v));
  return uint8_t(v);
}

/// The display colours, when the file has them, each from 0 to 255.
void readColours(const PlyMesh& ply, ResultFile& r) {
  const auto rgb = optionalColumns(ply.vertex, kColour);
  if (!rgb[0]) return;
  r.vertexColour.resize(r.positions.size());
  for (size_t i = 0; i < r.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) r.vertexColour[i][size_t(k)] = colourByte(*rgb[size_t(k)], i, r.path);
}

/// The vertex normals, when the file has them.
void readNormals(const PlyMesh& ply, ResultFile& r) {
  const auto n = optionalColumns(ply.vertex, kNormal);
  if (!n[0]) return;
  r.vertexNormal.resize(r.positions.size());
  for (size_t i = 0; i < r.positions.size(); ++i)
    r.vertexNormal[i] = glm::vec3(row(n.data(), i));
}

/// Face f's surface index: a whole number >= 0 within int.
int surfaceIndex(const PlyColumn& surface, size_t f, const std::string& path) {
  const double v = surface.values[f];
  if (!(v >= 0 && v < 2147483647.0 && v == std::floor(v)))
    throw inputError(path + ": face " + std::to_string(f) + ": surface", "a surface index >= 0", shortNumberText(v));
  return int(v);
}

/// The faces' surface indices, when the file has them.
void readSurfaces(const PlyMesh& ply, ResultFile& r) {
  const PlyColumn* surface = findColumn(ply.face, "surface");
  if (!surface) return;
  r.faceSurface.resize(r.faces.size());
  for (size_t f = 0; f < r.faces.size(); ++f) r.faceSurface[f] = surfaceIndex(*surface, f, r.path);
}

/// Face f's radiosity, finite and >= 0 in each channel.
glm::dvec3 faceRadiosity(const RequiredColumns& cols, size_t f, const std::string& path) {
  const glm::dvec3 b = row(cols.faceB, f);
  for (int k = 0; k < 3; ++k) checkRadiosity(b, k, path + ": face " + std::to_string(f));
  return b;
}

/// The elements' own radiosities (finite, >= 0).
void readFaceRadiosity(const RequiredColumns& cols, ResultFile& r) {
  r.faceRadiosity.resize(r.faces.size());
  for (size_t f = 0; f < r.faces.size(); ++f) r.faceRadiosity[f] = faceRadiosity(cols, f, r.path);
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

/// The vertices' parts: positions and radiosities, then the optional colours and normals.
void readVertexParts(const PlyMesh& ply, const RequiredColumns& cols, ResultFile& r) {
  readVertices(cols, r);
  readColours(ply, r);
  readNormals(ply, r);
}

/// The faces' parts: the triangles, then the optional surface indices and the radiosities.
void readFaceParts(const PlyMesh& ply, const RequiredColumns& cols, ResultFile& r) {
  r.faces = ply.faces;
  readSurfaces(ply, r);
  readFaceRadiosity(cols, r);
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

/// The result as a PLY mesh: comments, vertex columns, triangles and face columns.
PlyMesh resultPly(const ResultFile& result) {
  PlyMesh ply;
  ply.comments = comments(result);
  ply.vertex = vertexColumns(result);
  ply.faces = result.faces;
  ply.face = faceColumns(result);
  return ply;
}

}  // namespace

void writeResultFile(const std::string& path, const ResultFile& result) {
  checkSizes(result);
  writePly(path, resultPly(result));
}

ResultFile readResultFile(const std::string& path) {
  const PlyMesh ply = readPly(path);
  ResultFile r;
  r.path = path;
  const RequiredColumns cols = requiredColumns(ply, path);
  if (ply.faces.empty()) throw inputError(path, "a mesh with faces", "none");
  readVertexParts(ply, cols, r);
  readFaceParts(ply, cols, r);
  readComments(ply, r);
  return r;
}

}  // namespace rad
