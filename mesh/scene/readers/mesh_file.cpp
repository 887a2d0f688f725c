#include "mesh/scene/readers/mesh_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>

#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/base/ply_reader.h"
#include "mesh/scene/readers/gltf_reader.h"
#include "mesh/scene/readers/obj_reader.h"
#include "mesh/scene/readers/off_reader.h"

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

/// A file (or something else) is at the path.
void checkExists(const std::string& path, const std::string& where) {
  std::error_code missing;
  if (!std::filesystem::exists(path, missing))
    throw inputError(where, "a readable mesh file", "no file at " + path + (missing ? " (" + missing.message() + ")" : ""));
}

/// The path ends in .obj, .ply, .off, .gltf or .glb (any case) and names a file: its
/// extension, lower case.
std::string checkMeshPath(const std::string& path, const std::string& where) {
  const std::string ext = lowerExtension(path);
  if (ext != "obj" && ext != "ply" && ext != "off" && ext != "gltf" && ext != "glb")
    throw inputError(where, "a mesh file ending in .obj, .ply, .off, .gltf or .glb", path);
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
                                          const std::string& where, std::vector<std::string>& notes) {
  try {
    inputFileSize(path, "a readable mesh file");  // a FIFO or a folder: say so before reading
    if (ext == "gltf" || ext == "glb") return readGltfFile(path, notes);
    return ext == "obj" ? readObjFile(path, notes) : ext == "ply" ? readPlyMesh(path) : readOffFile(path);
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());  // the scene's place, then the file's
  }
}

}  // namespace

std::vector<MeshFileGroup> readMeshFile(const std::string& path, const std::string& where) {
  std::vector<std::string> unsaid;
  return readMeshFile(path, where, unsaid);
}

std::vector<MeshFileGroup> readMeshFile(const std::string& path, const std::string& where,
                                        std::vector<std::string>& notes) {
  std::vector<MeshFileGroup> groups = readMeshGroups(path, checkMeshPath(path, where), where, notes);
  if (faceCount(groups) == 0)
    throw inputError(where + ": " + path, "a mesh file with faces",
                     "none that parse (a damaged or empty file)");
  return groups;
}

}  // namespace rad
