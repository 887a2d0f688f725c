// Fuzz target: a result PLY as radview reads it (display/result_file.h).
#include "display/result_file.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rad::fuzz::readOrReject(data, size, "ply", [](const std::string& path) { rad::viewer::loadResult(path); });
}
