#pragma once
// Reading Geomview OFF meshes: "OFF", the vertex, face and edge counts, x y z per vertex, then
// "n i1 … in" per face. Counts are checked against the file's size before anything else.
#include <string>
#include <vector>

#include "mesh/scene/readers/mesh_file.h"

namespace rad {

/// An OFF file's faces, in one group. Throws InputError naming the file, line and what was found.
std::vector<MeshFileGroup> readOffFile(const std::string& path);

}  // namespace rad
