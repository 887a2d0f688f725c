#include "mesh/input_file.h"

#include <cstring>
#include <fstream>

#include <sys/stat.h>

#include "mesh/error.h"

namespace rad {
namespace {

std::string kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string mebibytes(uint64_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

uint64_t inputFileSize(const std::string& path, const std::string& what, uint64_t maxBytes) {
  struct stat st;
  if (stat(path.c_str(), &st) != 0) throw inputError(path, what, "no such file");
  if (!S_ISREG(st.st_mode)) throw inputError(path, what + " (a regular file)", kindOf(st.st_mode));
  const uint64_t size = uint64_t(st.st_size);
  if (size > maxBytes)
    throw inputError(path, what + " of at most " + mebibytes(maxBytes), "a file of " + mebibytes(size));
  return size;
}

std::string readInputFile(const std::string& path, const std::string& what, uint64_t maxBytes, bool text) {
  const uint64_t size = inputFileSize(path, what, maxBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw inputError(path, what, "a file that cannot be opened");
  std::string bytes(size_t(size), '\0');
  in.read(bytes.data(), std::streamsize(size));
  if (size_t(in.gcount()) != size) throw inputError(path, what, "a read error");
  if (text)
    if (const void* nul = std::memchr(bytes.data(), '\0', bytes.size()))
      throw inputError(path, what + " (text)", "a NUL byte at offset " +
                                                   std::to_string(static_cast<const char*>(nul) - bytes.data()));
  return bytes;
}

}  // namespace rad
