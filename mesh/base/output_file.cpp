#include "mesh/base/output_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include "mesh/base/error.h"

namespace rad {

namespace {

namespace fs = std::filesystem;

/// The folder a file is written in ("." for a bare name).
fs::path folderOf(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}

/// Writes the temporary file `temp` with `write` and renames it to `target` (named `path`
/// in messages); the caller removes `temp` on failure.
void writeAndRename(const fs::path& temp, const fs::path& target, const std::string& path,
                    const std::function<void(std::ostream&)>& write) {
  std::ofstream out(temp, std::ios::binary | std::ios::trunc);
  if (!out) throw inputError(path, "a writable output file", "a folder that refuses it");
  write(out);
  out.flush();
  if (!out) throw inputError(path, "the whole file written", "a write error");
  out.close();
  if (out.fail()) throw inputError(path, "the whole file written", "a write error on close");
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) throw inputError(path, "the output renamed into place", ec.message());
}

}  // namespace

void checkOutputPath(const std::string& path) {
  fs::path target(path);
  if (target.filename().empty() || fs::is_directory(target))
    throw inputError(path, "an output file name", "a folder");
  fs::path dir = folderOf(target);
  if (!fs::is_directory(dir))
    throw inputError(path, "an output file in an existing folder", "no folder " + dir.string());
}

void writeFileAtomically(const std::string& path,
                         const std::function<void(std::ostream&)>& write) {
  checkOutputPath(path);
  fs::path target(path);
  fs::path temp = folderOf(target) / ("." + target.filename().string() + "." + std::to_string(getpid()) + ".tmp");
  try {
    writeAndRename(temp, target, path, write);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

}  // namespace rad
