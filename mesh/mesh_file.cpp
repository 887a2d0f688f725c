#include "mesh/mesh_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <tiny_obj_loader.h>

#include "mesh/error.h"
#include "mesh/input_file.h"
#include "mesh/ply_reader.h"

namespace rad {
namespace {

/// The file name's extension in lower case ("" without one).
std::string lowerExtension(const std::string& path) {
  auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// The text without white space at either end.
std::string trimmed(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  size_t start = 0;
  while (start < s.size() && std::isspace(static_cast<unsigned char>(s[start]))) ++start;
  return s.substr(start);
}

/// tinyobjloader keeps a face's corner count in one byte.
constexpr int kMaxObjFaceVertices = 255;
/// At most this much MTL text per OBJ (every material file it names, each read once).
constexpr uint64_t kMaxMaterialBytes = uint64_t(64) << 20;

/// A finite number filling the whole word, or false.
bool finiteNumber(const std::string& word, double& v) {
  char* end = nullptr;
  v = std::strtod(word.c_str(), &end);
  return !word.empty() && *end == '\0' && std::isfinite(v);
}

/// The text with every line ending (LF, CRLF or, in old Mac files, CR alone) as LF.
std::string withLfLineEnds(const std::string& text) {
  std::string lf;
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] != '\r') lf += text[i];
    else if (i + 1 >= text.size() || text[i + 1] != '\n') lf += '\n';
  return lf;
}

/// The rest of the line after `key`: finite numbers.
void checkNumbers(std::istringstream& words, const std::string& key, const std::string& where) {
  std::string word;
  for (double v; words >> word;)
    if (!finiteNumber(word, v)) throw inputError(where, "finite numbers after '" + key + "'", "'" + word + "'");
}

/// Whether the word is a whole number naming one of `vertices` vertices: 1-based, or
/// negative counting back.
bool isVertexIndex(const std::string& word, long long vertices) {
  char* end = nullptr;
  errno = 0;
  const long long i = std::strtoll(word.c_str(), &end, 10);
  const bool inRange = i > 0 ? i <= vertices : i < 0 && uint64_t(-(i + 1)) < uint64_t(vertices);
  return !word.empty() && *end == '\0' && errno != ERANGE && inRange;
}

/// A face corner's word ("v", "v/vt", "v//vn" or "v/vt/vn"): its vertex index names one of the
/// `vertices` defined so far.
void checkCornerIndex(const std::string& word, long long vertices, const std::string& where) {
  const std::string first = word.substr(0, word.find('/'));
  if (!isVertexIndex(first, vertices))
    throw inputError(where, "vertex indices from 1 to " + std::to_string(vertices) + " (or -1 to -" +
                                std::to_string(vertices) + ", counting back)", "'" + first + "'");
}

/// The rest of a face (line, point) statement: indices of the `vertices` defined so far
/// (1-based, or negative counting back), at most kMaxObjFaceVertices of them.
void checkFaceIndices(std::istringstream& words, long long vertices, const std::string& where) {
  int corners = 0;
  for (std::string word; words >> word; ++corners) checkCornerIndex(word, vertices, where);
  // tinyobjloader counts a face's corners in one byte.
  if (corners > kMaxObjFaceVertices)
    throw inputError(where, "faces of at most " + std::to_string(kMaxObjFaceVertices) + " vertices",
                     std::to_string(corners));
}

/// One statement (`key`, then the rest of its line in `words`) of an OBJ or, if `material`, an
/// MTL text; `vertices` counts the vertex statements so far.
void checkObjStatement(const std::string& key, std::istringstream& words, bool material,
                       long long& vertices, const std::string& where) {
  // The colours we take (Kd, Ke) and the vertex positions: finite numbers (an RGB colour;
  // tinyobjloader reads neither spectral nor xyz colours).
  if (material ? (key == "Kd" || key == "Ke") : key == "v") {
    checkNumbers(words, key, where);
    vertices += key == "v";
  } else if (!material && (key == "f" || key == "l" || key == "p")) {
    checkFaceIndices(words, vertices, where);
  }
}

/// Checks the lines tinyobjloader would read leniently (it turns "nan" into 0 and clamps
/// indices): numbers after `v` and the colour keys of MTL are finite, and every face index
/// names a vertex defined before it (1-based, or negative counting back), line by line.
void checkObjText(const std::string& text, const std::string& path, bool material) {
  std::istringstream lines(withLfLineEnds(text));
  std::string line;
  long long vertices = 0;
  for (int n = 1; std::getline(lines, line); ++n) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string key;
    if (words >> key) checkObjStatement(key, words, material, vertices, path + ": line " + std::to_string(n));
  }
}

/// Appends the MTL file `name` (relative to the OBJ at `path`, named at `where`) to `text`,
/// unless it was read already.
void addMaterialFile(const std::string& path, const std::string& name, const std::string& where,
                     std::set<std::string>& read, std::string& text) {
  const std::string file = (std::filesystem::path(path).parent_path() / name).string();
  if (!read.insert(file).second) return;  // each file once, however often it is named
  const std::string mtl = readInputFile(file, "the material file (MTL) that " + where + " names", kMaxMaterialBytes);
  checkObjText(mtl, file, true);
  text += mtl + "\n";
  if (text.size() > kMaxMaterialBytes) throw inputError(where, "material files of at most 64 MiB in all", "more");
}

/// Line n of the OBJ at `path`: if it is an `mtllib` statement, the MTL files it names are
/// appended to `text`.
void addMaterialFiles(const std::string& line, int n, const std::string& path, std::set<std::string>& read,
                      std::string& text) {
  std::istringstream words(line);
  std::string word;
  if (!(words >> word) || word != "mtllib") return;
  const std::string where = path + ": line " + std::to_string(n);
  for (std::string name; words >> name;) addMaterialFile(path, name, where, read, text);
}

/// The text of every MTL file the OBJ names (`mtllib`), each read as an input file: tinyobj
/// gets text, never a path it would open itself.
std::string materialText(const std::string& obj, const std::string& path) {
  std::istringstream lines(obj);
  std::string line, text;
  std::set<std::string> read;
  for (int n = 1; std::getline(lines, line); ++n) addMaterialFiles(line, n, path, read, text);
  return text;
}

/// An MTL colour (three numbers at c), each finite.
glm::dvec3 finiteColour(const tinyobj::real_t* c, const std::string& where) {
  const glm::dvec3 v(c[0], c[1], c[2]);
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw inputError(where, "finite numbers", "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " +
                                                  std::to_string(v.z) + ")");
  return v;
}

/// The face's corner k as a vertex index, checked against the vertices the file has.
size_t objVertex(const tinyobj::index_t& index, size_t vertices, const std::string& where) {
  const int64_t vi = index.vertex_index;
  if (vi < 0 || uint64_t(vi) >= vertices)
    throw inputError(where, "vertex indices within the " + std::to_string(vertices) + " vertices defined",
                     "one outside them (" + std::to_string(vi + 1) + " counted from 1)");
  return size_t(vi);
}

/// The OBJ text parsed by tinyobjloader, with the MTL files it names; polygons stay polygons.
void parseObj(const std::string& obj, const std::string& path, tinyobj::ObjReader& reader) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // polygons stay polygons: the mesher triangulates them well
  if (!reader.ParseFromString(obj, materialText(obj, path), config)) {
    std::string why = trimmed(reader.Error());
    throw inputError(path, "a Wavefront OBJ file", "a parse error: " + why);
  }
}

/// Every vertex coordinate is finite.
void checkFiniteVertices(const tinyobj::attrib_t& attrib, const std::string& path) {
  for (size_t i = 0; i < attrib.vertices.size(); ++i)
    if (!std::isfinite(attrib.vertices[i]))
      throw inputError(path + ": vertex " + std::to_string(i / 3 + 1), "finite coordinates",
                       std::to_string(attrib.vertices[i]));
}

/// The shape's face corners add up to its indices.
void checkCorners(const tinyobj::shape_t& shape, const std::string& path) {
  size_t corners = 0;
  for (size_t n : shape.mesh.num_face_vertices) corners += n;
  if (corners != shape.mesh.indices.size())
    throw inputError(path + ": object " + shape.name, "faces whose corners add up to their indices",
                     std::to_string(corners) + " corners for " + std::to_string(shape.mesh.indices.size()) + " indices");
}

/// "<path>: object <name>: face <f + 1>" (the object left out when it has no name).
std::string faceWhere(const tinyobj::shape_t& shape, size_t f, const std::string& path) {
  return path + ": " + (shape.name.empty() ? "" : "object " + shape.name + ": ") + "face " + std::to_string(f + 1);
}

/// Vertex vi's position.
glm::dvec3 objPoint(const tinyobj::attrib_t& attrib, size_t vi) {
  return {attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1], attrib.vertices[3 * vi + 2]};
}

/// Face f of the shape, whose corners start at index `offset`, as a polygon.
Polygon objFace(const tinyobj::shape_t& shape, const tinyobj::attrib_t& attrib, size_t f,
                size_t offset, const std::string& path) {
  const std::string face = faceWhere(shape, f, path);
  const size_t n = shape.mesh.num_face_vertices[f];
  if (offset + n > shape.mesh.indices.size()) throw inputError(face, "its vertex indices", "fewer");
  const size_t vertices = attrib.vertices.size() / 3;
  Polygon polygon;
  for (size_t k = 0; k < n; ++k)
    polygon.outer.push_back(objPoint(attrib, objVertex(shape.mesh.indices[offset + k], vertices, face)));
  return polygon;
}

/// Face f's material id among `materials` (-1: none, or an unknown one).
int faceMaterial(const tinyobj::shape_t& shape, size_t f, int materials) {
  const int mat = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
  return mat >= materials ? -1 : mat;
}

/// Adds the shape's faces to the groups of their materials (-1: none, or an unknown one).
void addShapeFaces(const tinyobj::shape_t& shape, const tinyobj::attrib_t& attrib, int materials,
                   const std::string& path, std::map<int, MeshFileGroup>& groups) {
  checkCorners(shape, path);
  size_t offset = 0;
  for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
    Polygon polygon = objFace(shape, attrib, f, offset, path);
    offset += shape.mesh.num_face_vertices[f];
    groups[faceMaterial(shape, f, materials)].faces.push_back(std::move(polygon));
  }
}

/// The group takes the MTL material's name and colours (Kd, Ke: finite).
void nameGroup(const tinyobj::material_t& m, const std::string& path, MeshFileGroup& group) {
  group.material = m.name;
  group.kd = finiteColour(m.diffuse, path + ": material " + m.name + ": Kd");
  group.ke = finiteColour(m.emission, path + ": material " + m.name + ": Ke");
}

/// The groups in material order, each named with its MTL material's name and colours.
std::vector<MeshFileGroup> namedGroups(std::map<int, MeshFileGroup>& groups,
                                       const std::vector<tinyobj::material_t>& materials,
                                       const std::string& path) {
  std::vector<MeshFileGroup> out;
  for (auto& [id, group] : groups) {
    if (id >= 0) nameGroup(materials[size_t(id)], path, group);
    out.push_back(std::move(group));
  }
  return out;
}

/// A Wavefront OBJ: its faces grouped by MTL material (the faces without one in a group of
/// their own).
std::vector<MeshFileGroup> readObj(const std::string& path) {
  const std::string obj = readInputFile(path, "a Wavefront OBJ file");
  checkObjText(obj, path, false);
  tinyobj::ObjReader reader;
  parseObj(obj, path, reader);
  checkFiniteVertices(reader.GetAttrib(), path);
  std::map<int, MeshFileGroup> groups;  // by material id, -1 = none
  for (const auto& shape : reader.GetShapes())
    addShapeFaces(shape, reader.GetAttrib(), int(reader.GetMaterials().size()), path, groups);
  return namedGroups(groups, reader.GetMaterials(), path);
}

/// The PLY's x, y and z vertex columns: they are all there.
std::array<const PlyColumn*, 3> plyPositions(const PlyPolygons& ply, const std::string& path) {
  const std::array<const PlyColumn*, 3> xyz = {findColumn(ply.mesh.vertex, "x"), findColumn(ply.mesh.vertex, "y"),
                                               findColumn(ply.mesh.vertex, "z")};
  if (!xyz[0] || !xyz[1] || !xyz[2]) throw inputError(path, "a vertex element with x, y and z", "none");
  return xyz;
}

/// A PLY face (its vertex indices) as a polygon of the positions in columns `xyz`.
Polygon plyFace(const std::vector<int>& f, const std::array<const PlyColumn*, 3>& xyz) {
  Polygon face;
  for (int v : f) face.outer.emplace_back(xyz[0]->values[size_t(v)], xyz[1]->values[size_t(v)], xyz[2]->values[size_t(v)]);
  return face;
}

/// A PLY mesh: its vertices' x, y, z and its faces.
std::vector<MeshFileGroup> readPlyMesh(const std::string& path) {
  const PlyPolygons ply = readPlyPolygons(path);
  const auto xyz = plyPositions(ply, path);
  MeshFileGroup group;
  for (const auto& f : ply.faces) group.faces.push_back(plyFace(f, xyz));
  return {std::move(group)};
}

/// Words of an OFF file, '#' comments left out, each with its line for messages.
class OffWords {
 public:
  OffWords(const std::string& text, const std::string& path) : in_(text), path_(path) {}
  std::string where() const { return path_ + ": line " + std::to_string(line_); }
  bool next(std::string& word) {
    while (!(words_ >> word))
      if (!nextLine()) return false;
    return true;
  }
  double number(const char* what) {
    if (!next(word_)) throw inputError(where(), what, "the end of the file (a truncated file)");
    double v;
    if (!finiteNumber(word_, v)) throw inputError(where(), what, "'" + word_ + "'");
    return v;
  }
  uint64_t count(const char* what, uint64_t most) {
    const double v = number(what);
    if (v < 0 || v != std::floor(v) || v > double(most))
      throw inputError(where(), std::string(what) + " from 0 to " + std::to_string(most), "'" + word_ + "'");
    return uint64_t(v);
  }
  void skipLine() { words_.str(""), words_.clear(); }

 private:
  /// Moves on to the next line's words, its comment left out; false at the end.
  bool nextLine() {
    std::string line;
    if (!std::getline(in_, line)) return false;
    ++line_;
    words_.clear();
    words_.str(line.substr(0, line.find('#')));
    return true;
  }

  std::istringstream in_, words_;
  std::string path_, word_;
  int line_ = 0;
};

/// The keyword: OFF, with the optional prefixes for texture coordinates, colours and normals
/// after each vertex (skipped); 4OFF and nOFF (homogeneous, n-dimensional) are not 3D meshes.
void checkOffKeyword(OffWords& words) {
  std::string magic;
  static const std::set<std::string> keywords = {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCOFF", "STNOFF", "STCNOFF"};
  if (!words.next(magic) || !keywords.count(magic))
    throw inputError(words.where(), "the 'OFF' keyword (or COFF, NOFF, CNOFF, STOFF, STCOFF, STNOFF, STCNOFF)",
                     magic.empty() ? "nothing" : "'" + magic + "'");
}

/// The vertices' positions, one a line.
std::vector<glm::dvec3> readOffPoints(OffWords& words, uint64_t vertices) {
  std::vector<glm::dvec3> points(vertices);
  for (auto& p : points) {
    p = {words.number("a vertex x"), words.number("a vertex y"), words.number("a vertex z")};
    words.skipLine();  // colours or normals after the position are not ours
  }
  return points;
}

/// One face line: its vertex count and the indices of its vertices among `points`.
Polygon readOffFace(OffWords& words, const std::vector<glm::dvec3>& points) {
  const uint64_t n = words.count("a face's vertex count", kMaxPlyFaceVertices);
  if (points.empty() && n > 0) throw inputError(words.where(), "a face of the file's vertices", "a file without vertices");
  Polygon face;
  for (uint64_t k = 0; k < n; ++k) face.outer.push_back(points[words.count("a vertex index", points.size() - 1)]);
  words.skipLine();  // a face colour may follow
  return face;
}

/// The `faces` face lines, of vertices among `points`, as one group.
MeshFileGroup readOffFaces(OffWords& words, uint64_t faces, const std::vector<glm::dvec3>& points) {
  MeshFileGroup group;
  for (uint64_t f = 0; f < faces; ++f) group.faces.push_back(readOffFace(words, points));
  return group;
}

/// An OFF file (Geomview): "OFF", the vertex, face and edge counts, x y z per vertex, then
/// "n i1 … in" per face. Counts are checked against the file's size before anything else.
std::vector<MeshFileGroup> readOff(const std::string& path) {
  const std::string text = readInputFile(path, "an OFF file");
  OffWords words(text, path);
  checkOffKeyword(words);
  // Every vertex takes at least 6 bytes ("0 0 0\n"), every face 8 ("3 0 1 2\n").
  const uint64_t vertices = words.count("a vertex count", text.size() / 6);
  const uint64_t faces = words.count("a face count", text.size() / 8);
  words.count("an edge count", UINT64_MAX >> 12);
  return {readOffFaces(words, faces, readOffPoints(words, vertices))};
}

/// A file (or something else) is at the path.
void checkExists(const std::string& path, const std::string& where) {
  std::error_code missing;
  if (!std::filesystem::exists(path, missing))
    throw inputError(where, "a readable mesh file", "no file at " + path + (missing ? " (" + missing.message() + ")" : ""));
}

/// The path ends in .obj, .ply or .off (any case) and names a file: its extension, lower case.
std::string checkMeshPath(const std::string& path, const std::string& where) {
  const std::string ext = lowerExtension(path);
  if (ext != "obj" && ext != "ply" && ext != "off")
    throw inputError(where, "a mesh file ending in .obj, .ply or .off", path);
  checkExists(path, where);
  return ext;
}

/// The faces of every group.
size_t faceCount(const std::vector<MeshFileGroup>& groups) {
  size_t faces = 0;
  for (const auto& g : groups) faces += g.faces.size();
  return faces;
}

/// The groups of the mesh file at `path` (`ext` its checked extension); an error names the
/// scene's place (`where`), then the file's.
std::vector<MeshFileGroup> readMeshGroups(const std::string& path, const std::string& ext,
                                          const std::string& where) {
  try {
    inputFileSize(path, "a readable mesh file");  // a FIFO or a folder: say so before reading
    return ext == "obj" ? readObj(path) : ext == "ply" ? readPlyMesh(path) : readOff(path);
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());  // the scene's place, then the file's
  }
}

}  // namespace

std::vector<MeshFileGroup> readMeshFile(const std::string& path, const std::string& where) {
  std::vector<MeshFileGroup> groups = readMeshGroups(path, checkMeshPath(path, where), where);
  if (faceCount(groups) == 0)
    throw inputError(where + ": " + path, "a mesh file with faces",
                     "none that parse (a damaged or empty file)");
  return groups;
}

}  // namespace rad
