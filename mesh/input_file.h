#pragma once
// Reading input files so that a bad one fails at once with a located message: only regular
// files are read (a FIFO, a device or a folder is an error, not a wait), and sizes are checked
// before anything is allocated.
#include <cstdint>
#include <string>

namespace rad {

/// Largest scene file (JSON) read: a scene names its big geometry in mesh files.
constexpr uint64_t kMaxSceneFileBytes = uint64_t(64) << 20;
/// Largest mesh, result or reference file read (OBJ, MTL, PLY, OFF, CSV).
constexpr uint64_t kMaxInputFileBytes = uint64_t(4) << 30;

/// The size in bytes of the regular file at `path`; throws InputError "<path>: expected
/// <what>, found ..." when it is missing, not a regular file or larger than maxBytes.
uint64_t inputFileSize(const std::string& path, const std::string& what,
                       uint64_t maxBytes = kMaxInputFileBytes);

/// The whole of a regular file, checked as above; a text file (`text`) must hold no NUL byte.
std::string readInputFile(const std::string& path, const std::string& what,
                          uint64_t maxBytes = kMaxInputFileBytes, bool text = true);

}  // namespace rad
