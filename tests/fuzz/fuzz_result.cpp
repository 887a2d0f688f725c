// Fuzz target: a result PLY as radview and --fixed-point read it (mesh/results/result_file.h).
#include "mesh/results/result_file.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rad::fuzz::readOrReject(data, size, "ply", [](const std::string& path) { rad::readResultFile(path); });
}
