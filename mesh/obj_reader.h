#pragma once
// Reading Wavefront OBJ meshes with their MTL materials. The text is checked before
// tinyobjloader parses it (which would read bad numbers and indices leniently), and
// tinyobjloader gets the MTL text, never a path it would open itself.
#include <string>
#include <vector>

#include "mesh/mesh_file.h"

namespace rad {

/// An OBJ file's faces grouped by MTL material (the faces without one in a group of their
/// own, first). Throws InputError naming the file, line or face and what was found.
std::vector<MeshFileGroup> readObjFile(const std::string& path);

}  // namespace rad
