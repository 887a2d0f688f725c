#pragma once
// What every fuzz target shares: the input written to a file of the reader's kind (the readers
// take paths, as users give them), and the rule that bad input may only end in InputError.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include <unistd.h>

#include "mesh/base/error.h"

namespace rad::fuzz {

/// The input as a file ending in `extension` in the temporary folder, one per process.
inline std::string asFile(const uint8_t* data, size_t size, const std::string& extension) {
  const std::string path = "/tmp/rad_fuzz_" + std::to_string(getpid()) + "." + extension;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) __builtin_trap();
  if (size && std::fwrite(data, 1, size, f) != size) __builtin_trap();
  std::fclose(f);
  return path;
}

/// Runs `read` on the input file: an InputError (a located message) is the only allowed
/// failure; any other exception aborts, as a crash would.
template <class Read>
int readOrReject(const uint8_t* data, size_t size, const std::string& extension, Read read) {
  const std::string path = asFile(data, size, extension);
  try {
    read(path);
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace rad::fuzz
