// Fuzz target: the glTF reader (mesh/scene/readers/gltf_reader.h) through mesh/scene/readers/mesh_file.h, as a scene's mesh
// surface reads it; JSON or binary (.glb) alike, the reader tells them by their first bytes.
#include "mesh/scene/readers/mesh_file.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rad::fuzz::readOrReject(data, size, "gltf", [](const std::string& path) { rad::readMeshFile(path, "fuzz"); });
}
