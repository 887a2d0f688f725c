#include "mesh/output_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include "mesh/error.h"

namespace rad {

void checkOutputPath(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path target(path);
  if (target.filename().empty() || fs::is_directory(target))
    throw inputError(path, "an output file name", "a folder");
  fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(dir))
    throw inputError(path, "an output file in an existing folder", "no folder " + dir.string());
}

void writeFileAtomically(const std::string& path,
                         const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  checkOutputPath(path);
  fs::path target(path);
  fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  fs::path temp = dir / ("." + target.filename().string() + "." + std::to_string(getpid()) + ".tmp");
  try {
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
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

}  // namespace rad
