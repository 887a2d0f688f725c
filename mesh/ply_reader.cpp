#include "mesh/ply_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

#include "mesh/error.h"
#include "mesh/input_file.h"

namespace rad {
namespace {

/// A header line longer than this is not a PLY header.
constexpr size_t kMaxHeaderLine = 4096;

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

/// Byte size of a PLY scalar type, 0 if unknown.
int typeSize(const std::string& t) {
  static const std::map<std::string, int> sizes = {
      {"char", 1},  {"uchar", 1},  {"int8", 1},    {"uint8", 1},   {"short", 2},
      {"ushort", 2}, {"int16", 2}, {"uint16", 2},  {"int", 4},     {"uint", 4},
      {"int32", 4},  {"uint32", 4}, {"float", 4},  {"float32", 4}, {"double", 8},
      {"float64", 8}};
  auto it = sizes.find(t);
  return it == sizes.end() ? 0 : it->second;
}

struct Property {
  std::string name, type, countType;  // countType set for lists
};
struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};
struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::vector<std::string> comments;
  size_t body = 0;  // offset of the first byte after end_header
};

/// The fewest bytes one record of e takes in the file.
uint64_t minRecordBytes(const Element& e, Format format) {
  uint64_t bytes = 0;
  for (const auto& p : e.properties)
    bytes += format == Format::Ascii ? 2 : uint64_t(typeSize(p.countType.empty() ? p.type : p.countType));
  return std::max<uint64_t>(bytes, 1);
}

/// The next header line (without its line break), at most kMaxHeaderLine bytes.
bool headerLine(const std::string& bytes, size_t& at, std::string& line, const std::string& path) {
  if (at >= bytes.size()) return false;
  size_t end = bytes.find('\n', at);
  if (end == std::string::npos) end = bytes.size();
  if (end - at > kMaxHeaderLine)
    throw inputError(path, "PLY header lines of at most " + std::to_string(kMaxHeaderLine) + " bytes",
                     "a longer line");
  line = bytes.substr(at, end - at);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  at = std::min(end + 1, bytes.size());
  return true;
}

void addProperty(Header& h, std::istringstream& words, const std::string& line, const std::string& path) {
  if (h.elements.empty()) throw inputError(path, "an element before its properties", "'" + line + "'");
  Property p;
  words >> p.type;
  if (p.type == "list") words >> p.countType >> p.type;
  words >> p.name;
  if (p.name.empty() || !typeSize(p.type) || (p.type == "list") ||
      (!p.countType.empty() && (!typeSize(p.countType) || p.countType == "float" || p.countType == "double" ||
                                p.countType == "float32" || p.countType == "float64")))
    throw inputError(path, "a property with PLY scalar types (an integer count for a list) and a name",
                     "'" + line + "'");
  Element& e = h.elements.back();
  for (const auto& q : e.properties)
    if (q.name == p.name) throw inputError(path + ": element " + e.name, "each property once", "'" + p.name + "' twice");
  e.properties.push_back(p);
}

Header parseHeader(const std::string& bytes, const std::string& path) {
  Header h;
  size_t at = 0;
  std::string line;
  if (!headerLine(bytes, at, line, path) || line != "ply") throw inputError(path, "a PLY file", "no 'ply' magic line");
  bool format = false, ended = false;
  std::set<std::string> names;
  while (!ended && headerLine(bytes, at, line, path)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      std::string name, version;
      words >> name >> version;
      if (format) throw inputError(path, "one format line", "two");
      format = true;
      if (name == "ascii") h.format = Format::Ascii;
      else if (name == "binary_little_endian") h.format = Format::BinaryLittleEndian;
      else if (name == "binary_big_endian") h.format = Format::BinaryBigEndian;
      else throw inputError(path, "format ascii, binary_little_endian or binary_big_endian", "format " + name);
    } else if (word == "comment") {
      h.comments.push_back(line.size() > 8 ? line.substr(8) : "");
    } else if (word == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      char* end = nullptr;
      e.count = std::strtoull(count.c_str(), &end, 10);
      if (e.name.empty() || count.empty() || *end != '\0' || count[0] == '-')
        throw inputError(path, "'element <name> <count>'", "'" + line + "'");
      if (!names.insert(e.name).second) throw inputError(path, "each element once", "'" + e.name + "' twice");
      if (e.name == "vertex" && e.count > uint64_t(INT32_MAX))
        throw inputError(path + ": element vertex", "at most 2147483647 vertices", count);
      h.elements.push_back(e);
    } else if (word == "property") {
      addProperty(h, words, line, path);
    } else if (word == "end_header") {
      ended = true;
    } else if (word != "obj_info" && !word.empty()) {
      throw inputError(path, "a PLY header line (format, comment, element, property, end_header)", "'" + line + "'");
    }
  }
  if (!format || !ended) throw inputError(path, "a PLY header with a format line and end_header", "none");
  h.body = at;
  // Counts against the file's size, before anything is allocated.
  uint64_t needed = 0;
  for (const auto& e : h.elements) {
    const uint64_t record = minRecordBytes(e, h.format);
    if (e.count > (bytes.size() - h.body) / record || needed > bytes.size())
      throw inputError(path + ": element " + e.name,
                       "at most the " + std::to_string((bytes.size() - h.body) / record) + " records the file's size allows",
                       std::to_string(e.count) + " announced (a truncated file or a wrong count)");
    needed += e.count * record;
  }
  if (needed > bytes.size() - h.body)
    throw inputError(path, "a file as long as its header announces", "a truncated file");
  return h;
}

/// Reads the scalars of the body in order, in the file's format.
class BodyReader {
 public:
  BodyReader(const std::string& bytes, const Header& h, const std::string& path)
      : bytes_(bytes), at_(h.body), format_(h.format), path_(path) {}

  /// The next scalar of type t; `where` names it for messages.
  double scalar(const std::string& t, const std::string& where) {
    const double v = format_ == Format::Ascii ? asciiScalar(where) : binaryScalar(t, where);
    if (!std::isfinite(v)) throw inputError(where, "a finite number", std::to_string(v));
    return v;
  }

 private:
  double asciiScalar(const std::string& where) {
    while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    size_t end = at_;
    while (end < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[end]))) ++end;
    if (end == at_) throw inputError(where, "a number", "the end of the file (a truncated file)");
    const std::string word = bytes_.substr(at_, std::min<size_t>(end - at_, 64));
    char* stop = nullptr;
    const double v = std::strtod(word.c_str(), &stop);
    if (*stop != '\0' || end - at_ > 64) throw inputError(where, "a number", "'" + word + "'");
    at_ = end;
    return v;
  }

  double binaryScalar(const std::string& t, const std::string& where) {
    const size_t n = size_t(typeSize(t));
    if (bytes_.size() - at_ < n) throw inputError(where, "a " + t, "the end of the file (a truncated file)");
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + at_, n);
    if (format_ == Format::BinaryBigEndian) std::reverse(b, b + n);
    at_ += n;
    auto as = [&](auto v) {
      std::memcpy(&v, b, sizeof v);
      return double(v);
    };
    if (t == "char" || t == "int8") return as(int8_t());
    if (t == "uchar" || t == "uint8") return as(uint8_t());
    if (t == "short" || t == "int16") return as(int16_t());
    if (t == "ushort" || t == "uint16") return as(uint16_t());
    if (t == "int" || t == "int32") return as(int32_t());
    if (t == "uint" || t == "uint32") return as(uint32_t());
    if (t == "float" || t == "float32") return as(float());
    return as(double());
  }

  const std::string& bytes_;
  size_t at_;
  Format format_;
  const std::string& path_;
};

bool isFaceList(const Element& e, const Property& p) {
  return e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index");
}

/// A list's length, checked.
size_t listLength(BodyReader& body, const Property& p, const std::string& where, bool face) {
  const double n = body.scalar(p.countType, where);
  const double most = face ? double(kMaxPlyFaceVertices) : 1e6;
  if (n < (face ? 3 : 0) || n > most || n != std::floor(n))
    throw inputError(where, face ? "a face of 3 to " + std::to_string(kMaxPlyFaceVertices) + " vertices"
                                 : "a list length from 0 to 1000000",
                     std::to_string(n));
  return size_t(n);
}

PlyPolygons readBody(const std::string& bytes, const Header& h, const std::string& path) {
  PlyPolygons out;
  out.mesh.comments = h.comments;
  uint64_t vertices = 0;
  for (const auto& e : h.elements)
    if (e.name == "vertex") vertices = e.count;
  BodyReader body(bytes, h, path);
  for (const auto& e : h.elements) {
    const bool isVertex = e.name == "vertex", isFace = e.name == "face";
    int faceLists = 0;
    for (const auto& p : e.properties) faceLists += isFaceList(e, p);
    if (faceLists > 1) throw inputError(path + ": element face", "one vertex_indices list", "two");
    auto& columns = isVertex ? out.mesh.vertex : out.mesh.face;
    const size_t first = columns.size();
    if (isVertex || isFace)
      for (const auto& p : e.properties)
        if (p.countType.empty()) columns.push_back({p.name, PlyColumn::Type::Float, {}});
    for (uint64_t i = 0; i < e.count; ++i) {
      const std::string record = path + ": " + e.name + " " + std::to_string(i);
      size_t c = 0;
      for (const auto& p : e.properties) {
        const std::string where = record + ": " + p.name;
        if (p.countType.empty()) {
          const double v = body.scalar(p.type, where);
          if (isVertex || isFace) columns[first + c++].values.push_back(v);
          continue;
        }
        const bool face = isFaceList(e, p);
        const size_t n = listLength(body, p, where, face);
        std::vector<int> idx(face ? n : 0);
        for (size_t k = 0; k < n; ++k) {
          const double v = body.scalar(p.type, where);
          if (!face) continue;
          if (v < 0 || v >= double(vertices) || v != std::floor(v)) {
            char found[32];
            std::snprintf(found, sizeof found, "%.17g", v);
            throw inputError(where, vertices ? "vertex indices from 0 to " + std::to_string(vertices - 1)
                                             : std::string("no face (the file has no vertices)"), found);
          }
          idx[k] = int(v);
        }
        if (face) out.faces.push_back(std::move(idx));
      }
    }
  }
  return out;
}

/// A PLY file starts with its magic line.
void checkMagic(const std::string& head, const std::string& path) {
  if (head.compare(0, 4, "ply\n") != 0 && head.compare(0, 5, "ply\r\n") != 0)
    throw inputError(path, "a PLY file", "no 'ply' magic line");
}

}  // namespace

const PlyColumn* findColumn(const std::vector<PlyColumn>& columns, const std::string& name) {
  for (const auto& c : columns)
    if (c.name == name) return &c;
  return nullptr;
}

PlyPolygons readPlyPolygons(const std::string& path) {
  const std::string bytes = readInputFile(path, "a PLY file", kMaxInputFileBytes, false,
                                          [&](const std::string& head) { checkMagic(head, path); });
  const Header header = parseHeader(bytes, path);
  return readBody(bytes, header, path);
}

PlyMesh readPly(const std::string& path) {
  const std::string bytes = readInputFile(path, "a readable PLY file", kMaxInputFileBytes, false,
                                          [&](const std::string& head) { checkMagic(head, path); });
  const Header header = parseHeader(bytes, path);
  if (header.format != Format::BinaryLittleEndian)
    throw inputError(path, "binary_little_endian PLY",
                     std::string("format ") + (header.format == Format::Ascii ? "ascii" : "binary_big_endian"));
  PlyPolygons read = readBody(bytes, header, path);
  for (size_t f = 0; f < read.faces.size(); ++f) {
    if (read.faces[f].size() != 3)
      throw inputError(path + ": face " + std::to_string(f), "triangle faces",
                       "a face with " + std::to_string(read.faces[f].size()) + " vertices");
    read.mesh.faces.push_back({read.faces[f][0], read.faces[f][1], read.faces[f][2]});
  }
  return std::move(read.mesh);
}

}  // namespace rad
