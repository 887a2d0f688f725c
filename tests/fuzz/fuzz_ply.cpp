// Fuzz target: the PLY mesh reader (mesh/scene/readers/mesh_file.h), as a scene's mesh surface reads it.
#include "mesh/scene/readers/mesh_file.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rad::fuzz::readOrReject(data, size, "ply", [](const std::string& path) { rad::readMeshFile(path, "fuzz"); });
}
