// glTF 2.0 files ▸ groups of faces: the file loaded through tinygltf, its nodes placed down the
// hierarchy, and each primitive's positions and indices read from its accessors.
#include "mesh/scene/readers/gltf_reader.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/scene/readers/coplanar_faces.h"
#include "mesh/scene/readers/gltf_internal.h"

namespace rad::gltf {
namespace {

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

}  // namespace

// ---- Small readers of glTF values --------------------------------------------------------------

void checkNumbers(const std::vector<double>& values, size_t n, const std::string& where) {
  if (!values.empty() && values.size() != n)
    throw inputError(where, std::to_string(n) + " numbers", std::to_string(values.size()));
  for (double v : values)
    if (!std::isfinite(v)) throw inputError(where, "finite numbers", std::to_string(v));
}

std::string nameOr(const std::string& name, const std::string& kind, int index) {
  return name.empty() ? kind + std::to_string(index) : name;
}

namespace {

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

}  // namespace

// ---- The scene ---------------------------------------------------------------------------------

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

}  // namespace rad::gltf

namespace rad {

std::vector<MeshFileGroup> readGltfFile(const std::string& path, std::vector<std::string>& warnings) {
  gltf::GltfReader reader(gltf::loadModel(path), path);
  std::vector<MeshFileGroup> groups = reader.read();
  for (auto& g : groups) g.faces = mergeCoplanarFaces(g.faces);  // glTF has only triangles
  for (auto& w : reader.warnings()) warnings.push_back(std::move(w));
  return groups;
}

}  // namespace rad
