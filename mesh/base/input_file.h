#pragma once
// Reading input files so that a bad one fails at once with a located message: only regular
// files are read (a FIFO, a device or a folder is an error, not a wait), and sizes are checked
// before anything is allocated.
#include <cstdint>
#include <functional>
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

/// The first bytes read and checked before the rest (a zero-filled or foreign file of
/// gigabytes fails at once).
constexpr size_t kInputHeadBytes = 64 << 10;

/// The whole of a regular file, checked as above; a text file (`text`) must hold no NUL byte.
/// `checkHead`, if given, sees the first kInputHeadBytes (or the whole of a smaller file) before
/// the rest is read, and throws if they are not the file's kind.
std::string readInputFile(const std::string& path, const std::string& what,
                          uint64_t maxBytes = kMaxInputFileBytes, bool text = true,
                          const std::function<void(const std::string& head)>& checkHead = {});

}  // namespace rad
