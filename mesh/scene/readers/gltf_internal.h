#pragma once
// Internal to the glTF reader (gltf_reader.cpp, gltf_materials.cpp): the reader of tinygltf's
// model into groups of faces, the materials as a diffuse solver sees them, and the small readers
// of glTF values both files use. Not a public header: tinygltf's types stay in the reader.
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <tiny_gltf.h>

#include "mesh/base/error.h"
#include "mesh/scene/readers/mesh_file.h"

namespace rad::gltf {

/// Item `index` of a glTF array (`what`, for messages, at `where`), checked to exist.
template <class T>
const T& item(const std::vector<T>& items, int index, const std::string& what, const std::string& where) {
  if (index < 0 || size_t(index) >= items.size())
    throw inputError(where, "a " + what + " index from 0 to " + std::to_string(int(items.size()) - 1),
                     std::to_string(index));
  return items[size_t(index)];
}

/// `n` finite numbers (or none: the default) at `where`.
void checkNumbers(const std::vector<double>& values, size_t n, const std::string& where);

/// Names for messages and groups: the object's own, or `kind` and its index.
std::string nameOr(const std::string& name, const std::string& kind, int index);

/// A glTF material as a diffuse solver sees it.
struct GltfMaterial {
  std::string name;
  glm::dvec3 kd{1.0}, ke{0.0};  ///< reflectance; emitted radiance
  bool textured = false, metallic = false, transmissive = false, white = false;
  std::string unreadTexture;  ///< why its base-colour texture could not be read, if so
};

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

}  // namespace rad::gltf
