#pragma once
// Reading glTF 2.0 scenes (.gltf with its buffers and images, or .glb) through tinygltf, whose
// types stay inside the reader (gltf_reader.cpp, gltf_materials.cpp, gltf_internal.h).
#include <string>
#include <vector>

#include "mesh/scene/readers/mesh_file.h"

namespace rad {

/// The triangles of every mesh primitive of the file's default scene (of every scene when it
/// names none), placed by their nodes' transforms (parents' composed down the hierarchy) and
/// grouped by node and material, coplanar neighbours merged back into polygons
/// (mesh/scene/readers/coplanar_faces.h): group "<node>/<material>", `kd` the base colour (its texture's
/// mean colour times baseColorFactor), `ke` emissiveFactor × KHR_materials_emissive_strength
/// (radiance, as MTL Ke). What was approximated (textures as their mean, an unreadable one left
/// out, metals, glass, white, points and lines left out) is said once per file in `warnings`, a
/// sentence per kind naming the materials or meshes. Throws InputError naming the file and what
/// was expected and found (malformed JSON or GLB, a missing buffer, an index or accessor out of
/// range, NaN positions).
std::vector<MeshFileGroup> readGltfFile(const std::string& path, std::vector<std::string>& warnings);

}  // namespace rad
