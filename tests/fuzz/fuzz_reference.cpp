// Fuzz target: the reference CSV (mesh/results/reference_points.h), as solve --reference reads it.
#include "mesh/results/reference_points.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rad::fuzz::readOrReject(data, size, "csv", [](const std::string& path) { rad::readReferenceFile(path); });
}
