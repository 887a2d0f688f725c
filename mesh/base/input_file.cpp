#include "mesh/base/input_file.h"

#include <cstring>
#include <fstream>

#include <sys/stat.h>

#include "mesh/base/error.h"

namespace rad {
namespace {

/// What a file that is not a regular one is, for messages.
std::string kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

/// The size of the regular file at `path` (`what` it should be, for messages).
uint64_t regularFileSize(const std::string& path, const std::string& what) {
  struct stat st;
  if (stat(path.c_str(), &st) != 0) throw inputError(path, what, "no such file");
  if (!S_ISREG(st.st_mode)) throw inputError(path, what + " (a regular file)", kindOf(st.st_mode));
  return uint64_t(st.st_size);
}

/// A size in whole MiB, for messages.
std::string mebibytes(uint64_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

/// An open input file, with what it should be (for messages) and whether it is text.
struct Source {
  std::ifstream& in;
  const std::string& path;
  const std::string& what;
  bool text;
};

/// Reads on until `bytes` holds upTo bytes; a text file may hold no NUL byte.
void readMore(const Source& s, std::string& bytes, size_t upTo) {
  const size_t from = bytes.size();
  bytes.resize(upTo);
  s.in.read(bytes.data() + from, std::streamsize(upTo - from));
  if (size_t(s.in.gcount()) != upTo - from) throw inputError(s.path, s.what, "a read error");
  if (s.text)
    if (const void* nul = std::memchr(bytes.data() + from, '\0', upTo - from))
      throw inputError(s.path, s.what + " (text)", "a NUL byte at offset " +
                                                       std::to_string(static_cast<const char*>(nul) - bytes.data()));
}

}  // namespace

uint64_t inputFileSize(const std::string& path, const std::string& what, uint64_t maxBytes) {
  const uint64_t size = regularFileSize(path, what);
  if (size > maxBytes)
    throw inputError(path, what + " of at most " + mebibytes(maxBytes), "a file of " + mebibytes(size));
  return size;
}

std::string readInputFile(const std::string& path, const std::string& what, uint64_t maxBytes, bool text,
                          const std::function<void(const std::string&)>& checkHead) {
  const uint64_t size = inputFileSize(path, what, maxBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw inputError(path, what, "a file that cannot be opened");
  const Source source{in, path, what, text};
  std::string bytes;
  readMore(source, bytes, size_t(std::min<uint64_t>(size, kInputHeadBytes)));
  if (checkHead) checkHead(bytes);
  readMore(source, bytes, size_t(size));
  return bytes;
}

}  // namespace rad
