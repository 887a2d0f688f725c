// Fuzz target: the scene loader (mesh/scene/scene.h) on the input as JSON text, mesh files resolved
// against tests/data (so that the seeds' box.obj and friends are found).
#include "mesh/scene/readers/scene_loader.h"
#include "tests/fuzz/fuzz_input.h"

#ifndef RAD_DATA_DIR
#define RAD_DATA_DIR "tests/data"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    rad::parseScene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json", RAD_DATA_DIR);
  } catch (const rad::InputError&) {
  }
  return 0;
}
