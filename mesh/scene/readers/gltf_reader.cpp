#include "mesh/scene/readers/gltf_reader.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "mesh/scene/readers/coplanar_faces.h"
#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/scene/readers/texture_mean.h"

namespace rad {
namespace {

/// A material whose metallicFactor is above this is a metal: radiosity keeps its diffuse part.
constexpr double kMetallic = 0.5;
/// A base colour of 1 (white) would reflect all light and the solve never converge: its
/// brightest channel becomes this, the others in proportion.
constexpr double kMaxReflectance = 0.95;
/// At most this many triangles per file: far beyond what a radiosity solve meshes in minutes,
/// and a bound on what a small file instancing a mesh many times can make us allocate.
constexpr size_t kMaxTriangles = size_t(1) << 22;

using Triangle = std::array<uint64_t, 3>;

// ---- Loading the file with tinygltf ----------------------------------------------------------

/// tinygltf's messages on one line.
std::string oneLine(const std::string& text) {
  std::istringstream lines(text);
  std::string out;
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
  return out.empty() ? "no message" : out;
}

/// tinygltf's file test: a regular file is at the path.
bool fileExists(const std::string& path, void*) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error);
}

/// tinygltf's path expansion: none (no `~` or `$VAR` taken from a file's contents).
std::string samePath(const std::string& path, void*) { return path; }

/// tinygltf's file reading, with the checks of every input file (a regular file, its size).
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  try {
    const std::string bytes = readInputFile(path, "a buffer or image file", kMaxInputFileBytes, false);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const InputError& e) {
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}

/// tinygltf's file writing: never.
bool writeNothing(std::string* err, const std::string& path, const std::vector<unsigned char>&, void*) {
  if (err) *err += "not writing " + path + "\n";
  return false;
}

/// tinygltf's image loader: keeps an image file's or data URI's bytes encoded, so that only
/// base-colour textures are decoded. An image in a buffer view is read later, once its view is
/// checked to lie in its buffer (tinygltf passes it unchecked).
bool keepEncoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                 const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

/// The loader, reading files only through the project's checks and decoding no image.
void configure(tinygltf::TinyGLTF& loader) {
  loader.SetFsCallbacks({fileExists, samePath, readWholeFile, writeNothing, nullptr});
  loader.SetImageLoader(keepEncoded, nullptr);
}

/// tinygltf's parse of `bytes` (binary or JSON), its buffers and images beside the file in
/// `folder`; false with `err` when it fails.
bool parseModel(const std::string& bytes, bool binary, const std::string& folder, tinygltf::Model& model,
                std::string& err) {
  tinygltf::TinyGLTF loader;
  configure(loader);
  std::string warn;  // what it skips (a missing image) we find and say ourselves
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  try {
    return binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, unsigned(bytes.size()), folder)
                  : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), folder);
  } catch (const std::exception& e) {  // tinygltf throws on a few malformed inputs (an empty data URI)
    err += e.what();
    return false;
  }
}

/// The glTF file at `path` as tinygltf reads it, with its buffers and encoded images: binary
/// (.glb) when it starts with the magic "glTF", JSON otherwise, whatever its extension.
tinygltf::Model loadModel(const std::string& path) {
  const std::string bytes = readInputFile(path, "a glTF 2.0 file", uint64_t(UINT_MAX), false);
  const bool binary = bytes.compare(0, 4, "glTF") == 0;
  const std::string what = binary ? "a binary glTF 2.0 file (.glb)" : "a glTF 2.0 file (JSON)";
  tinygltf::Model model;
  std::string err;
  if (!parseModel(bytes, binary, std::filesystem::path(path).parent_path().string(), model, err))
    throw inputError(path, what + " whose buffers load", "errors: " + oneLine(err));
  if (model.asset.version.substr(0, 2) != "2.")
    throw inputError(path + ": asset.version", "2.0 (glTF 2)", "'" + model.asset.version + "'");
  return model;
}

// ---- Small readers of glTF values --------------------------------------------------------------

/// Item `index` of a glTF array (`what`, for messages, at `where`), checked to exist.
template <class T>
const T& item(const std::vector<T>& items, int index, const std::string& what, const std::string& where) {
  if (index < 0 || size_t(index) >= items.size())
    throw inputError(where, "a " + what + " index from 0 to " + std::to_string(int(items.size()) - 1),
                     std::to_string(index));
  return items[size_t(index)];
}

/// `n` finite numbers (or none: the default) at `where`.
void checkNumbers(const std::vector<double>& values, size_t n, const std::string& where) {
  if (!values.empty() && values.size() != n)
    throw inputError(where, std::to_string(n) + " numbers", std::to_string(values.size()));
  for (double v : values)
    if (!std::isfinite(v)) throw inputError(where, "finite numbers", std::to_string(v));
}

/// The node's own transform: its matrix, or translation × rotation × scale (glTF 2.0 §3.5.3).
glm::dmat4 localTransform(const tinygltf::Node& n, const std::string& where) {
  checkNumbers(n.matrix, 16, where + ": matrix");
  checkNumbers(n.translation, 3, where + ": translation");
  checkNumbers(n.rotation, 4, where + ": rotation");
  checkNumbers(n.scale, 3, where + ": scale");
  if (!n.matrix.empty()) return glm::make_mat4(n.matrix.data());  // column-major, as GLM's
  glm::dmat4 m(1.0);
  if (!n.translation.empty()) m = glm::translate(m, glm::make_vec3(n.translation.data()));
  if (!n.rotation.empty()) {
    const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);  // stored x, y, z, w
    if (!(glm::length(q) > 0)) throw inputError(where + ": rotation", "a unit quaternion", "(0, 0, 0, 0)");
    m *= glm::mat4_cast(glm::normalize(q));
  }
  if (!n.scale.empty()) m = glm::scale(m, glm::make_vec3(n.scale.data()));
  return m;
}

/// Bytes per component of a glTF component type (0: not one).
size_t componentBytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return 4;
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

/// The integer of component type `type` (an integer type) at p.
int64_t integerAt(const unsigned char* p, int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return int8_t(p[0]);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p, 2); return v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return v; }
    case TINYGLTF_COMPONENT_TYPE_INT: { int32_t v; std::memcpy(&v, p, 4); return v; }
    default: { uint32_t v; std::memcpy(&v, p, 4); return v; }
  }
}

/// An accessor's type and component type, for messages ("VEC3 of 5126").
std::string typeName(const tinygltf::Accessor& a) {
  const std::map<int, std::string> names = {{TINYGLTF_TYPE_SCALAR, "SCALAR"}, {TINYGLTF_TYPE_VEC2, "VEC2"},
                                            {TINYGLTF_TYPE_VEC3, "VEC3"},     {TINYGLTF_TYPE_VEC4, "VEC4"},
                                            {TINYGLTF_TYPE_MAT4, "MAT4"}};
  const auto named = names.find(a.type);
  return (named != names.end() ? named->second : "type " + std::to_string(a.type)) + " of component type " +
         std::to_string(a.componentType);
}

/// The triangles of a primitive's corner indices in `mode` (TRIANGLES, TRIANGLE_STRIP or
/// TRIANGLE_FAN), with the winding glTF 2.0 §3.7.2.1 gives each.
std::vector<Triangle> assemble(const std::vector<uint64_t>& v, int mode, const std::string& where) {
  std::vector<Triangle> out;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (v.size() % 3) throw inputError(where, "a multiple of 3 indices for triangles", std::to_string(v.size()));
    for (size_t i = 0; i + 2 < v.size(); i += 3) out.push_back({v[i], v[i + 1], v[i + 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < v.size(); ++i) out.push_back({v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
  } else {
    for (size_t i = 1; i + 1 < v.size(); ++i) out.push_back({v[i], v[i + 1], v[0]});
  }
  return out;
}

/// Whether a primitive of this mode has faces: TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN.
bool isSurface(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

/// Names for messages and groups: the object's own, or `kind` and its index.
std::string nameOr(const std::string& name, const std::string& kind, int index) {
  return name.empty() ? kind + std::to_string(index) : name;
}

/// The items in a list: a, b.
std::string joined(const std::set<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

/// A list of names in quotes: 'a', 'b'.
std::string quoted(const std::set<std::string>& names) {
  std::set<std::string> inQuotes;
  for (const auto& n : names) inQuotes.insert("'" + n + "'");
  return joined(inQuotes);
}

// ---- Materials ---------------------------------------------------------------------------------

/// A glTF material as a diffuse solver sees it.
struct GltfMaterial {
  std::string name;
  glm::dvec3 kd{1.0}, ke{0.0};  ///< reflectance; emitted radiance
  bool textured = false, metallic = false, transmissive = false, white = false;
  std::string unreadTexture;  ///< why its base-colour texture could not be read, if so
};

/// baseColorFactor's RGB (white when absent), each in [0, 1].
glm::dvec3 baseColourFactor(const tinygltf::PbrMetallicRoughness& pbr, const std::string& where) {
  checkNumbers(pbr.baseColorFactor, 4, where);
  if (pbr.baseColorFactor.empty()) return glm::dvec3(1.0);
  for (int c = 0; c < 3; ++c)
    if (!(pbr.baseColorFactor[size_t(c)] >= 0 && pbr.baseColorFactor[size_t(c)] <= 1))
      throw inputError(where, "numbers in [0, 1]", std::to_string(pbr.baseColorFactor[size_t(c)]));
  return glm::make_vec3(pbr.baseColorFactor.data());
}

/// The number `key` of the material's extension `extension` (`otherwise` when absent), finite
/// and >= 0.
double extensionNumber(const tinygltf::Material& m, const std::string& extension, const std::string& key,
                       double otherwise, const std::string& where) {
  const auto found = m.extensions.find(extension);
  if (found == m.extensions.end() || !found->second.Has(key)) return otherwise;
  const tinygltf::Value& v = found->second.Get(key);
  const double x = v.IsNumber() ? v.GetNumberAsDouble() : -1;
  if (!(std::isfinite(x) && x >= 0))
    throw inputError(where + ": " + extension + "." + key, "a finite number >= 0",
                     v.IsNumber() ? std::to_string(x) : "not a number");
  return x;
}

/// The emitted radiance: emissiveFactor × KHR_materials_emissive_strength's emissiveStrength.
glm::dvec3 emittedRadiance(const tinygltf::Material& m, const std::string& where) {
  checkNumbers(m.emissiveFactor, 3, where + ": emissiveFactor");
  const glm::dvec3 factor = m.emissiveFactor.empty() ? glm::dvec3(0.0) : glm::make_vec3(m.emissiveFactor.data());
  if (!(factor.x >= 0 && factor.y >= 0 && factor.z >= 0))
    throw inputError(where + ": emissiveFactor", "numbers >= 0", "a negative one");
  return factor * extensionNumber(m, "KHR_materials_emissive_strength", "emissiveStrength", 1.0, where);
}

/// A base colour of 1 or more in some channel scaled so that its brightest is kMaxReflectance;
/// whether it was.
bool capWhite(glm::dvec3& kd) {
  const double brightest = std::max({kd.x, kd.y, kd.z});
  if (brightest < 1) return false;
  kd *= kMaxReflectance / brightest;
  return true;
}

// ---- The scene ---------------------------------------------------------------------------------

/// A node placed in the scene: its index and its world transform.
struct PlacedNode {
  int node = 0;
  glm::dmat4 world{1.0};
};

/// A bounded run of bytes in a buffer.
struct Bytes {
  const unsigned char* data = nullptr;
  size_t size = 0;
};

/// The glTF file read into groups of faces by node and material, with what was approximated.
class GltfReader {
 public:
  GltfReader(tinygltf::Model model, std::string path) : model_(std::move(model)), path_(std::move(path)) {}

  /// Every mesh primitive of the placed nodes, as groups in the order first met.
  std::vector<MeshFileGroup> read() {
    for (const PlacedNode& placed : placedNodes()) addNode(placed);
    return std::move(groups_);
  }

  /// What was approximated or left out, a sentence each.
  std::vector<std::string> warnings() const;

 private:
  std::vector<int> rootNodes() const;
  std::vector<PlacedNode> placedNodes() const;
  void addNode(const PlacedNode& placed);
  void addPrimitive(const PlacedNode& placed, const tinygltf::Primitive& p, const std::string& label,
                    const std::string& meshName, size_t k);
  Bytes viewBytes(int view, const std::string& where) const;
  Bytes accessorBytes(const tinygltf::Accessor& a, size_t elementBytes, size_t& stride, const std::string& where) const;
  std::vector<glm::dvec3> positions(const tinygltf::Primitive& p, const std::string& where) const;
  std::vector<uint64_t> indices(const tinygltf::Primitive& p, size_t vertices, const std::string& where) const;
  const GltfMaterial& material(int index);
  GltfMaterial readMaterial(int index) const;
  Bytes imageBytes(int texture, const std::string& where, std::string& label) const;
  void applyTexture(int texture, const std::string& where, GltfMaterial& m) const;
  MeshFileGroup& group(const std::string& label, const GltfMaterial& m, int index);

  tinygltf::Model model_;
  std::string path_;
  std::vector<MeshFileGroup> groups_;
  std::map<std::pair<std::string, int>, size_t> groupOf_;  ///< (node label, material) -> group
  std::map<int, GltfMaterial> materials_;                   ///< read once, on first use
  std::map<int, size_t> facesOf_;                           ///< faces per material
  std::set<std::string> pointsAndLines_;                    ///< meshes with primitives left out
  size_t leftOut_ = 0, triangles_ = 0;
};

/// The default scene's root nodes; without one, every scene's; without scenes, the nodes no
/// node names as a child.
std::vector<int> GltfReader::rootNodes() const {
  if (model_.defaultScene >= 0) return item(model_.scenes, model_.defaultScene, "scene", path_ + ": scene").nodes;
  std::vector<int> roots;
  for (const auto& s : model_.scenes) roots.insert(roots.end(), s.nodes.begin(), s.nodes.end());
  if (!model_.scenes.empty()) return roots;
  std::vector<bool> child(model_.nodes.size(), false);
  for (const auto& n : model_.nodes)
    for (int c : n.children)
      if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
  for (size_t i = 0; i < child.size(); ++i)
    if (!child[i]) roots.push_back(int(i));
  return roots;
}

/// The nodes under the roots, depth first in file order, each with its world transform (its
/// parents' composed with its own). A node reached twice (glTF forbids it) is placed once.
std::vector<PlacedNode> GltfReader::placedNodes() const {
  std::vector<PlacedNode> placed, stack;
  const std::vector<int> roots = rootNodes();
  for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, glm::dmat4(1.0)});
  std::vector<bool> seen(model_.nodes.size(), false);
  while (!stack.empty()) {
    PlacedNode p = stack.back();
    stack.pop_back();
    const std::string where = path_ + ": node " + std::to_string(p.node);
    const tinygltf::Node& n = item(model_.nodes, p.node, "node", where);
    if (seen[size_t(p.node)]) continue;
    seen[size_t(p.node)] = true;
    p.world = p.world * localTransform(n, where);
    placed.push_back(p);
    for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, p.world});
  }
  return placed;
}

/// The node's mesh, every primitive of it, placed by the node's world transform.
void GltfReader::addNode(const PlacedNode& placed) {
  const tinygltf::Node& node = model_.nodes[size_t(placed.node)];
  if (node.mesh < 0) return;
  const std::string at = path_ + ": node " + std::to_string(placed.node);
  const tinygltf::Mesh& mesh = item(model_.meshes, node.mesh, "mesh", at + ": mesh");
  const std::string meshName = nameOr(mesh.name, "mesh", node.mesh);
  const std::string label = node.name.empty() ? meshName : node.name;
  for (size_t k = 0; k < mesh.primitives.size(); ++k)
    addPrimitive(placed, mesh.primitives[k], label, meshName, k);
}

/// Primitive k of mesh `meshName`: its triangles added to the group of (node label, its
/// material), moved by the node's world transform; points and lines are counted and left out.
void GltfReader::addPrimitive(const PlacedNode& placed, const tinygltf::Primitive& p, const std::string& label,
                              const std::string& meshName, size_t k) {
  if (!isSurface(p.mode)) {
    ++leftOut_;
    pointsAndLines_.insert(meshName);
    return;
  }
  const std::string where = path_ + ": mesh '" + meshName + "': primitive " + std::to_string(k);
  const std::vector<glm::dvec3> points = positions(p, where);
  const std::vector<Triangle> triangles = assemble(indices(p, points.size(), where), p.mode, where);
  triangles_ += triangles.size();
  if (triangles_ > kMaxTriangles)
    throw inputError(path_, "at most 4 194 304 triangles in all (simplify the model)", "more");
  const bool mirrored = glm::determinant(placed.world) < 0;  // glTF 2.0 §3.7.4: the winding flips
  MeshFileGroup& g = group(label, material(p.material), p.material);
  for (const Triangle& t : triangles) {
    Polygon face;
    for (uint64_t v : t) face.outer.push_back(glm::dvec3(placed.world * glm::dvec4(points[v], 1.0)));
    if (mirrored) std::reverse(face.outer.begin(), face.outer.end());
    g.faces.push_back(std::move(face));
  }
  facesOf_[p.material] += triangles.size();
}

/// The bytes of buffer view `view`, checked to lie in its buffer.
Bytes GltfReader::viewBytes(int view, const std::string& where) const {
  const tinygltf::BufferView& v =
      item(model_.bufferViews, view, "buffer view (compressed meshes such as Draco are not read)", where);
  const std::string at = path_ + ": bufferView " + std::to_string(view);
  const tinygltf::Buffer& b = item(model_.buffers, v.buffer, "buffer", at);
  if (v.byteOffset > b.data.size() || v.byteLength > b.data.size() - v.byteOffset)
    throw inputError(at, "bytes within its buffer's " + std::to_string(b.data.size()),
                     "bytes " + std::to_string(v.byteOffset) + " to " + std::to_string(v.byteOffset + v.byteLength));
  return {b.data.data() + v.byteOffset, v.byteLength};
}

/// The bytes of accessor a's elements (`elementBytes` each, `stride` apart), checked to lie in
/// its buffer view.
Bytes GltfReader::accessorBytes(const tinygltf::Accessor& a, size_t elementBytes, size_t& stride,
                                const std::string& where) const {
  if (a.sparse.isSparse) throw inputError(where, "an accessor without sparse storage", "a sparse one");
  const Bytes view = viewBytes(a.bufferView, where + ": bufferView");
  const tinygltf::BufferView& v = model_.bufferViews[size_t(a.bufferView)];
  stride = v.byteStride ? v.byteStride : elementBytes;
  const size_t room = a.byteOffset <= view.size ? view.size - a.byteOffset : 0;
  const bool fits = stride >= elementBytes &&
                    (a.count == 0 || (room >= elementBytes && (a.count - 1) <= (room - elementBytes) / stride));
  if (a.byteOffset > view.size || !fits)
    throw inputError(where,
                     std::to_string(a.count) + " elements of " + std::to_string(elementBytes) + " bytes, " +
                         std::to_string(stride) + " apart, from byte " + std::to_string(a.byteOffset) + " of its view",
                     "a view of " + std::to_string(view.size) + " bytes");
  return {view.data + a.byteOffset, a.count == 0 ? 0 : (a.count - 1) * stride + elementBytes};
}

/// The primitive's vertex positions (VEC3 of float), finite.
std::vector<glm::dvec3> GltfReader::positions(const tinygltf::Primitive& p, const std::string& where) const {
  const auto attribute = p.attributes.find("POSITION");
  if (attribute == p.attributes.end()) throw inputError(where, "a POSITION attribute", "none");
  const std::string at = where + ": POSITION accessor " + std::to_string(attribute->second);
  const tinygltf::Accessor& a = item(model_.accessors, attribute->second, "accessor", at);
  if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw inputError(at, "positions as VEC3 of FLOAT (5126)", typeName(a));
  size_t stride = 0;
  const Bytes bytes = accessorBytes(a, 12, stride, at);
  std::vector<glm::dvec3> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    float xyz[3];
    std::memcpy(xyz, bytes.data + i * stride, sizeof xyz);
    out[i] = glm::dvec3(xyz[0], xyz[1], xyz[2]);
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
      throw inputError(at + ": vertex " + std::to_string(i), "finite coordinates", "NaN or infinity");
  }
  return out;
}

/// The primitive's corner indices (0 to vertices − 1; all vertices in order when it has none).
std::vector<uint64_t> GltfReader::indices(const tinygltf::Primitive& p, size_t vertices,
                                          const std::string& where) const {
  std::vector<uint64_t> out;
  if (p.indices < 0) {
    for (size_t i = 0; i < vertices; ++i) out.push_back(i);
    return out;
  }
  const std::string at = where + ": indices accessor " + std::to_string(p.indices);
  const tinygltf::Accessor& a = item(model_.accessors, p.indices, "accessor", at);
  const size_t bytes = componentBytes(a.componentType);
  if (a.type != TINYGLTF_TYPE_SCALAR || bytes == 0 || a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw inputError(at, "SCALAR integer indices", typeName(a));
  size_t stride = 0;
  const Bytes data = accessorBytes(a, bytes, stride, at);
  for (size_t i = 0; i < a.count; ++i) {
    const int64_t v = integerAt(data.data + i * stride, a.componentType);
    if (v < 0 || uint64_t(v) >= vertices)
      throw inputError(at + ": index " + std::to_string(i),
                       "a vertex from 0 to " + std::to_string(int64_t(vertices) - 1), std::to_string(v));
    out.push_back(uint64_t(v));
  }
  return out;
}

/// Material `index` (-1: glTF's default, white), read on first use.
const GltfMaterial& GltfReader::material(int index) {
  auto found = materials_.find(index);
  if (found == materials_.end()) found = materials_.emplace(index, readMaterial(index)).first;
  return found->second;
}

/// Material `index` as a diffuse solver sees it: reflectance, emitted radiance, and what it
/// approximates.
GltfMaterial GltfReader::readMaterial(int index) const {
  GltfMaterial out;
  if (index < 0) {
    out.name = "default";
    out.white = capWhite(out.kd);
    return out;
  }
  const tinygltf::Material& m = item(model_.materials, index, "material", path_ + ": primitive material");
  out.name = nameOr(m.name, "material", index);
  const std::string where = path_ + ": material '" + out.name + "'";
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  out.kd = baseColourFactor(pbr, where + ": baseColorFactor");
  if (pbr.baseColorTexture.index >= 0) applyTexture(pbr.baseColorTexture.index, where + ": baseColorTexture", out);
  out.white = capWhite(out.kd);
  out.ke = emittedRadiance(m, where);
  out.metallic = pbr.metallicFactor > kMetallic;
  out.transmissive = extensionNumber(m, "KHR_materials_transmission", "transmissionFactor", 0.0, where) > 0;
  return out;
}

/// The encoded bytes of texture `texture`'s image (a file, a data URI or a buffer view; none
/// when its file could not be read), and its name for messages in `label`.
Bytes GltfReader::imageBytes(int texture, const std::string& where, std::string& label) const {
  const tinygltf::Texture& t = item(model_.textures, texture, "texture", where);
  const std::string at = where + ": texture " + std::to_string(texture) + ": source";
  const tinygltf::Image& image = item(model_.images, t.source, "PNG or JPEG image", at);
  label = image.uri.empty() ? "image " + std::to_string(t.source) : "'" + image.uri + "'";
  if (image.bufferView >= 0) return viewBytes(image.bufferView, path_ + ": " + label + ": bufferView");
  return {image.image.data(), image.image.size()};
}

/// The material's base colour times the linear mean colour of texture `texture`; when the image
/// cannot be read or decoded (a texture missing beside a downloaded file), the factor alone,
/// and why in `unreadTexture`. A texture the file names wrongly is an error.
void GltfReader::applyTexture(int texture, const std::string& where, GltfMaterial& m) const {
  std::string label;
  const Bytes bytes = imageBytes(texture, where, label);
  try {
    if (bytes.size == 0) throw inputError(label, "an image file beside the glTF file", "none that could be read");
    m.kd *= meanLinearColour(bytes.data, bytes.size, label);
    m.textured = true;
  } catch (const InputError& e) {
    m.unreadTexture = e.what();
  }
}

/// The group of (node label, material `index`), made on first use: "<label>/<material>".
MeshFileGroup& GltfReader::group(const std::string& label, const GltfMaterial& m, int index) {
  const auto [found, added] = groupOf_.emplace(std::make_pair(label, index), groups_.size());
  if (added) {
    groups_.emplace_back();
    groups_.back().material = label + "/" + m.name;
    groups_.back().kd = m.kd;
    groups_.back().ke = m.ke;
  }
  return groups_[found->second];
}

std::vector<std::string> GltfReader::warnings() const {
  std::set<std::string> textured, unread, white, approximated;
  size_t approximatedFaces = 0;
  for (const auto& [index, m] : materials_) {
    if (m.textured) textured.insert(m.name);
    if (!m.unreadTexture.empty()) unread.insert("'" + m.name + "' (" + m.unreadTexture + ")");
    if (m.white) white.insert(m.name);
    if (m.metallic || m.transmissive) approximatedFaces += facesOf_.at(index);
    if (m.metallic) approximated.insert(m.name + " (metallic)");
    if (m.transmissive) approximated.insert(m.name + " (transmissive)");
  }
  std::vector<std::string> out;
  if (!textured.empty())
    out.push_back("materials " + quoted(textured) + ": reflectance is the mean colour of the base-colour texture "
                  "times baseColorFactor (a radiosity solve keeps no texture detail)");
  if (!unread.empty())
    out.push_back("materials " + joined(unread) + ": base-colour texture not read, baseColorFactor alone is the "
                  "reflectance (put the image beside the glTF file)");
  if (!approximated.empty())
    out.push_back(std::to_string(approximatedFaces) + " faces of materials " + quoted(approximated) +
                  " treated as diffuse with their base colour (radiosity has no mirrors or glass; set metallicFactor "
                  "to 0 and leave out KHR_materials_transmission to say so in the file)");
  if (!white.empty())
    out.push_back("materials " + quoted(white) + ": base colour 1 (white) would reflect all light; taken as "
                  "reflectance 0.95 (hue kept); give a baseColorFactor below 1 to choose");
  if (leftOut_)
    out.push_back("left out " + std::to_string(leftOut_) + " primitives drawn as points or lines (not "
                  "surfaces) in meshes " + quoted(pointsAndLines_));
  return out;
}

}  // namespace

std::vector<MeshFileGroup> readGltfFile(const std::string& path, std::vector<std::string>& warnings) {
  GltfReader reader(loadModel(path), path);
  std::vector<MeshFileGroup> groups = reader.read();
  for (auto& g : groups) g.faces = mergeCoplanarFaces(g.faces);  // glTF has only triangles
  for (auto& w : reader.warnings()) warnings.push_back(std::move(w));
  return groups;
}

}  // namespace rad
