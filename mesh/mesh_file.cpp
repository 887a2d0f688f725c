#include "mesh/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <tiny_obj_loader.h>

#include "mesh/error.h"

namespace rad {
namespace {

std::string lowerExtension(const std::string& path) {
  auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::vector<MeshFileGroup> readObj(const std::string& path, const std::string& where) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // polygons stay polygons: the mesher triangulates them well
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string why = reader.Error();
    while (!why.empty() && std::isspace(static_cast<unsigned char>(why.back()))) why.pop_back();
    throw inputError(where + ": " + path, "a Wavefront OBJ file", "a parse error: " + why);
  }
  const auto& attrib = reader.GetAttrib();
  const auto& materials = reader.GetMaterials();
  std::map<int, MeshFileGroup> groups;  // by material id, -1 = none
  for (const auto& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      int n = shape.mesh.num_face_vertices[f];
      Polygon face;
      for (int k = 0; k < n; ++k) {
        int vi = shape.mesh.indices[offset + k].vertex_index;
        face.outer.emplace_back(attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1],
                                attrib.vertices[3 * vi + 2]);
      }
      offset += n;
      int mat = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      groups[mat].faces.push_back(std::move(face));
    }
  }
  std::vector<MeshFileGroup> out;
  for (auto& [id, group] : groups) {
    if (id >= 0) {
      const auto& m = materials[id];
      group.material = m.name;
      group.kd = glm::dvec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
      group.ke = glm::dvec3(m.emission[0], m.emission[1], m.emission[2]);
    }
    out.push_back(std::move(group));
  }
  return out;
}

std::vector<MeshFileGroup> readWithOpenMesh(const std::string& path, const std::string& where) {
  OpenMesh::PolyMesh_ArrayKernelT<> mesh;
  OpenMesh::IO::Options options;
  // OpenMesh prints its complaints on stderr; our error message says what went wrong.
  omerr().disable();
  bool ok = OpenMesh::IO::read_mesh(mesh, path, options);
  omerr().enable();
  if (!ok)
    throw inputError(where + ": " + path, "a " + lowerExtension(path) + " mesh file",
                     "a file OpenMesh cannot parse");
  MeshFileGroup group;
  for (auto f : mesh.faces()) {
    Polygon face;
    for (auto v : mesh.fv_range(f)) {
      const auto& p = mesh.point(v);
      face.outer.emplace_back(p[0], p[1], p[2]);
    }
    group.faces.push_back(std::move(face));
  }
  return {std::move(group)};
}

}  // namespace

std::vector<MeshFileGroup> readMeshFile(const std::string& path, const std::string& where) {
  if (!std::ifstream(path))
    throw inputError(where, "a readable mesh file", "no file at " + path);
  std::string ext = lowerExtension(path);
  std::vector<MeshFileGroup> groups;
  if (ext == "obj")
    groups = readObj(path, where);
  else if (ext == "ply" || ext == "off")
    groups = readWithOpenMesh(path, where);
  else
    throw inputError(where, "a mesh file ending in .obj, .ply or .off", path);
  size_t faces = 0;
  for (const auto& g : groups) faces += g.faces.size();
  if (faces == 0)
    throw inputError(where + ": " + path, "a mesh file with faces",
                     "none that parse (a damaged or empty file)");
  return groups;
}

}  // namespace rad
