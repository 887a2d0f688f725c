#pragma once
// Reading Wavefront OBJ meshes with their MTL materials. The text is checked before
// tinyobjloader parses it (which would read bad numbers and indices leniently), and
// tinyobjloader gets the MTL text, never a path it would open itself.
#include <string>
#include <vector>

#include "mesh/scene/readers/mesh_file.h"

namespace rad {

/// An OBJ file's faces grouped by MTL material (the faces without one in a group of their
/// own, first). A material with a diffuse texture (map_Kd) takes its mean colour times Kd; one
/// whose specular part outweighs its diffuse one, or that is transparent, keeps its diffuse
/// part: both are said in `notes`. Throws InputError naming the file, line or face and what was
/// found.
std::vector<MeshFileGroup> readObjFile(const std::string& path, std::vector<std::string>& notes);

}  // namespace rad
