#include "mesh/scene/readers/obj_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <tiny_obj_loader.h>

#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/base/number_text.h"
#include "mesh/scene/readers/texture_mean.h"

namespace rad {
namespace {

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

/// A face has at most kMaxObjFaceVertices corners: tinyobjloader counts them in one byte.
void checkCornerCount(int corners, const std::string& where) {
  if (corners > kMaxObjFaceVertices)
    throw inputError(where, "faces of at most " + std::to_string(kMaxObjFaceVertices) + " vertices",
                     std::to_string(corners));
}

/// The rest of a face (line, point) statement: indices of the `vertices` defined so far
/// (1-based, or negative counting back), at most kMaxObjFaceVertices of them.
void checkFaceIndices(std::istringstream& words, long long vertices, const std::string& where) {
  int corners = 0;
  for (std::string word; words >> word; ++corners) checkCornerIndex(word, vertices, where);
  checkCornerCount(corners, where);
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

/// The file `name` relative to the folder of the file at `path`.
std::string besideFile(const std::string& path, const std::string& name) {
  return (std::filesystem::path(path).parent_path() / name).string();
}

/// Appends the MTL file `name` (relative to the OBJ at `path`, named at `where`) to `text`,
/// unless it was read already.
void addMaterialFile(const std::string& path, const std::string& name, const std::string& where,
                     std::set<std::string>& read, std::string& text) {
  const std::string file = besideFile(path, name);
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

/// tinyobjloader's settings: polygons stay polygons.
tinyobj::ObjReaderConfig objConfig() {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // polygons stay polygons: the mesher triangulates them well
  return config;
}

/// The OBJ text parsed by tinyobjloader, with the MTL files it names; polygons stay polygons.
void parseObj(const std::string& obj, const std::string& path, tinyobj::ObjReader& reader) {
  if (!reader.ParseFromString(obj, materialText(obj, path), objConfig())) {
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

/// A group's key: its material id (-1: none, or an unknown one), then its object's place among
/// the file's objects (`o`/`g` names) in order of first appearance.
using GroupKey = std::pair<int, int>;

/// Adds the shape's faces to the groups of their object and material.
void addShapeFaces(const tinyobj::shape_t& shape, const tinyobj::attrib_t& attrib, int materials, int object,
                   const std::string& path, std::map<GroupKey, MeshFileGroup>& groups) {
  checkCorners(shape, path);
  size_t offset = 0;
  for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
    Polygon polygon = objFace(shape, attrib, f, offset, path);
    offset += shape.mesh.num_face_vertices[f];
    MeshFileGroup& group = groups[{faceMaterial(shape, f, materials), object}];
    group.object = shape.name;
    group.faces.push_back(std::move(polygon));
  }
}

/// At most this much texture file per material.
constexpr uint64_t kMaxTextureBytes = uint64_t(256) << 20;

/// What reading the materials approximated, said once per file.
struct Approximations {
  std::vector<std::string> textured, unreadTextures, diffuseOnly;  // in the MTL's order
  size_t diffuseOnlyFaces = 0;
};

/// The largest channel.
double largest(const glm::dvec3& c) { return std::max({c.x, c.y, c.z}); }

/// Material m's diffuse texture (map_Kd, beside the OBJ) as its mean colour times Kd (the
/// texture alone where Kd is black, as when the MTL leaves it out); Kd where the texture cannot
/// be read, which `said` notes.
glm::dvec3 texturedDiffuse(const tinyobj::material_t& m, const glm::dvec3& kd, const std::string& path,
                           Approximations& said) {
  const std::string file = besideFile(path, m.diffuse_texname);
  try {
    const std::string bytes = readInputFile(file, "the texture (map_Kd) of material " + m.name, kMaxTextureBytes, false);
    const glm::dvec3 mean = meanLinearColour(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), file);
    said.textured.push_back(m.name);
    return mean * (largest(kd) > 0 ? kd : glm::dvec3(1.0));
  } catch (const InputError& e) {
    said.unreadTextures.push_back(m.name + " (" + e.what() + ")");
    return kd;
  }
}

/// Why material m is more than its diffuse part (`kd`): its specular part outweighs it, or it is
/// transparent (d < 1, or an MTL illumination model with refraction or transparency); or "".
std::string beyondDiffuse(const tinyobj::material_t& m, const glm::dvec3& kd) {
  const glm::dvec3 ks(m.specular[0], m.specular[1], m.specular[2]);
  char why[96] = "";
  if (m.dissolve < 1 || m.illum == 4 || m.illum == 6 || m.illum == 7 || m.illum == 9)
    std::snprintf(why, sizeof why, "transparent: illum %d, d %g", m.illum, double(m.dissolve));
  else if (largest(ks) > largest(kd))
    std::snprintf(why, sizeof why, "Ks %g above Kd %g", largest(ks), largest(kd));
  return why;
}

/// An MTL material's colours as groups take them: Kd (or its texture's mean) and Ke.
struct MaterialColours {
  glm::dvec3 kd{0.0}, ke{0.0};
};

/// Material m's colours, noting in `said` what was approximated (once per material).
MaterialColours materialColours(const tinyobj::material_t& m, const std::string& path, Approximations& said) {
  MaterialColours c;
  c.kd = finiteColour(m.diffuse, path + ": material " + m.name + ": Kd");
  c.ke = finiteColour(m.emission, path + ": material " + m.name + ": Ke");
  if (!m.diffuse_texname.empty()) c.kd = texturedDiffuse(m, c.kd, path, said);
  const std::string why = beyondDiffuse(m, c.kd);
  if (!why.empty()) said.diffuseOnly.push_back(m.name + " (" + why + ")");
  return c;
}

/// The group takes MTL material m's name and colours; its faces count as approximated when
/// the material is.
void nameGroup(const tinyobj::material_t& m, const MaterialColours& c, MeshFileGroup& group, Approximations& said) {
  group.material = m.name;
  group.kd = c.kd;
  group.ke = c.ke;
  if (!beyondDiffuse(m, c.kd).empty()) said.diffuseOnlyFaces += group.faces.size();
}

/// The names, comma-separated.
std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// What was approximated, a sentence per kind.
void addNotes(const Approximations& said, std::vector<std::string>& notes) {
  if (!said.diffuseOnly.empty())
    notes.push_back(std::to_string(said.diffuseOnlyFaces) + " faces of material(s) " + listed(said.diffuseOnly) +
                    " are treated as their diffuse part (Kd): this solver shows diffuse light only");
  if (!said.textured.empty())
    notes.push_back("material(s) " + listed(said.textured) + " take their map_Kd texture's mean colour (times Kd)");
  if (!said.unreadTextures.empty())
    notes.push_back("material(s) " + listed(said.unreadTextures) + ": texture not read, Kd used");
}

/// The groups in material order (objects in file order within one), each named with its MTL
/// material's name and colours; what that approximated goes into `notes`.
std::vector<MeshFileGroup> namedGroups(std::map<GroupKey, MeshFileGroup>& groups,
                                       const std::vector<tinyobj::material_t>& materials,
                                       const std::string& path, std::vector<std::string>& notes) {
  std::vector<MeshFileGroup> out;
  Approximations said;
  std::map<int, MaterialColours> colours;  // once per material, however many objects use it
  for (auto& [key, group] : groups) {
    const int id = key.first;
    if (id >= 0) {
      if (!colours.count(id)) colours[id] = materialColours(materials[size_t(id)], path, said);
      nameGroup(materials[size_t(id)], colours[id], group, said);
    }
    out.push_back(std::move(group));
  }
  addNotes(said, notes);
  return out;
}

/// Every shape's faces, grouped by material id (-1: none) and object.
std::map<GroupKey, MeshFileGroup> facesByMaterial(const tinyobj::ObjReader& reader, const std::string& path) {
  std::map<GroupKey, MeshFileGroup> groups;
  std::map<std::string, int> objects;  // name -> order of first appearance
  for (const auto& shape : reader.GetShapes()) {
    const int object = objects.emplace(shape.name, int(objects.size())).first->second;
    addShapeFaces(shape, reader.GetAttrib(), int(reader.GetMaterials().size()), object, path, groups);
  }
  return groups;
}

}  // namespace

std::vector<MeshFileGroup> readObjFile(const std::string& path, std::vector<std::string>& notes) {
  const std::string obj = readInputFile(path, "a Wavefront OBJ file");
  checkObjText(obj, path, false);
  tinyobj::ObjReader reader;
  parseObj(obj, path, reader);
  checkFiniteVertices(reader.GetAttrib(), path);
  std::map<GroupKey, MeshFileGroup> groups = facesByMaterial(reader, path);
  return namedGroups(groups, reader.GetMaterials(), path, notes);
}

}  // namespace rad
