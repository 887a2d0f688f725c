#pragma once
// Reading polygon meshes from OBJ (with MTL), PLY and OFF files.
#include <optional>
#include <string>
#include <vector>

#include "mesh/scene/scene.h"

namespace rad {

/// The faces of a mesh file that share one material (and, in an OBJ, one object).
struct MeshFileGroup {
  std::string material;                 ///< the MTL material name; empty when the file has none
  std::string object;                   ///< the OBJ object or group (`o`, `g`) its faces are in, if named
  std::optional<glm::dvec3> kd, ke;     ///< MTL diffuse colour and radiance, when given
  std::vector<Polygon> faces;
};

/// Reads an OBJ (faces grouped by MTL material and object), PLY or OFF file (one group), or a glTF file
/// (one group per node and material, coplanar triangles merged back into polygons). `where` prefixes error messages. Throws InputError if the file is
/// missing or does not parse. What the reader approximated (a material's specular or
/// transparent part left out, a texture taken as its mean colour) is added to `notes`, a
/// sentence per kind naming the materials.
std::vector<MeshFileGroup> readMeshFile(const std::string& path, const std::string& where,
                                        std::vector<std::string>& notes);

/// The same, the notes left unsaid (tests and fuzzing).
std::vector<MeshFileGroup> readMeshFile(const std::string& path, const std::string& where);

}  // namespace rad
