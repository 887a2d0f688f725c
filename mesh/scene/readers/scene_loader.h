#pragma once
// The scene file (DESIGN.md, "Scene file"): read, validated, and every mesh file it names read
// (mesh/scene/readers/mesh_file.h).
#include <string>

#include "mesh/scene/scene.h"

namespace rad {

/// Reads and validates a version-1 scene file and every mesh file it names.
/// Throws InputError naming the file, the JSON path, what was expected and what was found.
Scene loadScene(const std::string& path);

/// Parses a scene from JSON text; mesh files are resolved against baseDir.
Scene parseScene(const std::string& text, const std::string& path, const std::string& baseDir);

}  // namespace rad
