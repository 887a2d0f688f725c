#include "mesh/base/ply_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/base/number_text.h"

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

/// The line without a CR at its end (a CRLF line break).
std::string withoutCr(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

/// The end of the header line at `at` (its '\n', or the end of the bytes); the line is at most
/// kMaxHeaderLine bytes.
size_t headerLineEnd(const std::string& bytes, size_t at, const std::string& path) {
  size_t end = bytes.find('\n', at);
  if (end == std::string::npos) end = bytes.size();
  if (end - at > kMaxHeaderLine)
    throw inputError(path, "PLY header lines of at most " + std::to_string(kMaxHeaderLine) + " bytes",
                     "a longer line");
  return end;
}

/// The next header line (without its line break), at most kMaxHeaderLine bytes.
bool headerLine(const std::string& bytes, size_t& at, std::string& line, const std::string& path) {
  if (at >= bytes.size()) return false;
  const size_t end = headerLineEnd(bytes, at, path);
  line = withoutCr(bytes.substr(at, end - at));
  at = std::min(end + 1, bytes.size());
  return true;
}

/// The rest of a property line: "<type> <name>" or "list <count type> <type> <name>".
Property propertyOf(std::istringstream& words) {
  Property p;
  words >> p.type;
  if (p.type == "list") words >> p.countType >> p.type;
  words >> p.name;
  return p;
}

/// A named property of a scalar type, or a list of them counted by an integer type.
bool wellTyped(const Property& p) {
  const std::string& c = p.countType;
  const bool integerCount = typeSize(c) && c != "float" && c != "double" && c != "float32" && c != "float64";
  return !p.name.empty() && typeSize(p.type) && p.type != "list" && (c.empty() || integerCount);
}

/// Element e has no property named p yet.
void checkNewProperty(const Element& e, const Property& p, const std::string& path) {
  for (const auto& q : e.properties)
    if (q.name == p.name) throw inputError(path + ": element " + e.name, "each property once", "'" + p.name + "' twice");
}

/// A property line: a well-typed property of the last element, named once.
void addProperty(Header& h, std::istringstream& words, const std::string& line, const std::string& path) {
  if (h.elements.empty()) throw inputError(path, "an element before its properties", "'" + line + "'");
  const Property p = propertyOf(words);
  if (!wellTyped(p))
    throw inputError(path, "a property with PLY scalar types (an integer count for a list) and a name",
                     "'" + line + "'");
  checkNewProperty(h.elements.back(), p, path);
  h.elements.back().properties.push_back(p);
}

/// The format a format line names: ascii, binary_little_endian or binary_big_endian.
Format formatNamed(const std::string& name, const std::string& path) {
  if (name == "ascii") return Format::Ascii;
  if (name == "binary_little_endian") return Format::BinaryLittleEndian;
  if (name == "binary_big_endian") return Format::BinaryBigEndian;
  throw inputError(path, "format ascii, binary_little_endian or binary_big_endian", "format " + name);
}

/// A format line: ascii, binary_little_endian or binary_big_endian, once.
void readFormat(Header& h, std::istringstream& words, bool& format, const std::string& path) {
  std::string name, version;
  words >> name >> version;
  if (format) throw inputError(path, "one format line", "two");
  format = true;
  h.format = formatNamed(name, path);
}

/// The rest of an element line: "<name> <count>", the count a whole number (`count` its text).
Element elementOf(std::istringstream& words, const std::string& line, std::string& count,
                  const std::string& path) {
  Element e;
  words >> e.name >> count;
  char* end = nullptr;
  e.count = std::strtoull(count.c_str(), &end, 10);
  if (e.name.empty() || count.empty() || *end != '\0' || count[0] == '-')
    throw inputError(path, "'element <name> <count>'", "'" + line + "'");
  return e;
}

/// A vertex element has at most INT32_MAX records (`count` as written).
void checkVertexCount(const Element& e, const std::string& count, const std::string& path) {
  if (e.name == "vertex" && e.count > uint64_t(INT32_MAX))
    throw inputError(path + ": element vertex", "at most 2147483647 vertices", count);
}

/// An element line: a new name and a count (at most INT32_MAX vertices).
void addElement(Header& h, std::istringstream& words, const std::string& line,
                std::set<std::string>& names, const std::string& path) {
  std::string count;
  const Element e = elementOf(words, line, count, path);
  if (!names.insert(e.name).second) throw inputError(path, "each element once", "'" + e.name + "' twice");
  checkVertexCount(e, count, path);
  h.elements.push_back(e);
}

/// What the header lines say so far.
struct HeaderState {
  bool format = false, ended = false;
  std::set<std::string> names;  ///< of the elements
};

/// One header line after the magic.
void headerLineInto(Header& h, const std::string& line, HeaderState& st, const std::string& path) {
  std::istringstream words(line);
  std::string word;
  words >> word;
  if (word == "format") readFormat(h, words, st.format, path);
  else if (word == "comment") h.comments.push_back(line.size() > 8 ? line.substr(8) : "");
  else if (word == "element") addElement(h, words, line, st.names, path);
  else if (word == "property") addProperty(h, words, line, path);
  else if (word == "end_header") st.ended = true;
  else if (word != "obj_info" && !word.empty())
    throw inputError(path, "a PLY header line (format, comment, element, property, end_header)", "'" + line + "'");
}

/// The fewest bytes element e's records take; they fit in the `room` after the header (with
/// `needed` bytes announced before them, of `bytes` in all).
uint64_t elementBytes(const Element& e, Format format, uint64_t room, uint64_t needed, size_t bytes,
                      const std::string& path) {
  const uint64_t record = minRecordBytes(e, format);
  if (e.count > room / record || needed > bytes)
    throw inputError(path + ": element " + e.name,
                     "at most the " + std::to_string(room / record) + " records the file's size allows",
                     std::to_string(e.count) + " announced (a truncated file or a wrong count)");
  return e.count * record;
}

/// Counts against the file's size (`bytes` in all), before anything is allocated.
void checkCounts(const Header& h, size_t bytes, const std::string& path) {
  uint64_t needed = 0;
  for (const auto& e : h.elements) needed += elementBytes(e, h.format, bytes - h.body, needed, bytes, path);
  if (needed > bytes - h.body) throw inputError(path, "a file as long as its header announces", "a truncated file");
}

/// The header lines after the magic, into h, up to end_header; `at` ends after it.
void readHeaderLines(const std::string& bytes, size_t& at, Header& h, const std::string& path) {
  std::string line;
  HeaderState st;
  while (!st.ended && headerLine(bytes, at, line, path)) headerLineInto(h, line, st, path);
  if (!st.format || !st.ended) throw inputError(path, "a PLY header with a format line and end_header", "none");
}

/// The first header line is the magic "ply"; `at` ends after it.
void checkMagicLine(const std::string& bytes, size_t& at, const std::string& path) {
  std::string line;
  if (!headerLine(bytes, at, line, path) || line != "ply") throw inputError(path, "a PLY file", "no 'ply' magic line");
}

/// The header, checked line by line and against the file's size.
Header parseHeader(const std::string& bytes, const std::string& path) {
  Header h;
  size_t at = 0;
  checkMagicLine(bytes, at, path);
  readHeaderLines(bytes, at, h, path);
  h.body = at;
  checkCounts(h, bytes.size(), path);
  return h;
}

/// Reads the scalars of the body in order, in the file's format.
class BodyReader {
 public:
  BodyReader(const std::string& bytes, const Header& h) : bytes_(bytes), at_(h.body), format_(h.format) {}

  /// The next scalar of type t; `where` names it for messages.
  double scalar(const std::string& t, const std::string& where) {
    const double v = format_ == Format::Ascii ? asciiScalar(where) : binaryScalar(t, where);
    if (!std::isfinite(v)) throw inputError(where, "a finite number", std::to_string(v));
    return v;
  }

 private:
  /// Whether byte i is in the body and white space.
  bool spaceAt(size_t i) const { return i < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[i])); }
  /// Whether byte i is in the body and not white space.
  bool wordAt(size_t i) const { return i < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[i])); }

  /// Skips white space: the end of the word that follows (at_ itself at the end of the body).
  size_t wordEnd() {
    while (spaceAt(at_)) ++at_;
    size_t end = at_;
    while (wordAt(end)) ++end;
    return end;
  }

  /// The word as a number; a word cut at 64 bytes (`cut`) is none.
  static double asciiNumber(const std::string& word, bool cut, const std::string& where) {
    char* stop = nullptr;
    const double v = std::strtod(word.c_str(), &stop);
    if (*stop != '\0' || cut) throw inputError(where, "a number", "'" + word + "'");
    return v;
  }

  /// The next word of an ascii body as a number.
  double asciiScalar(const std::string& where) {
    const size_t end = wordEnd();
    if (end == at_) throw inputError(where, "a number", "the end of the file (a truncated file)");
    const double v = asciiNumber(bytes_.substr(at_, std::min<size_t>(end - at_, 64)), end - at_ > 64, where);
    at_ = end;
    return v;
  }

  /// The next scalar of type t in a binary body.
  double binaryScalar(const std::string& t, const std::string& where) {
    const size_t n = size_t(typeSize(t));
    if (bytes_.size() - at_ < n) throw inputError(where, "a " + t, "the end of the file (a truncated file)");
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + at_, n);
    if (format_ == Format::BinaryBigEndian) std::reverse(b, b + n);
    at_ += n;
    return decode(t, b);
  }

  /// The scalar of type t in the bytes b, in this machine's order.
  static double decode(const std::string& t, const unsigned char* b) {
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
};

/// Whether p is the face element's list of vertex indices.
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

/// v as a face's vertex index: a whole number naming one of `vertices` vertices.
int vertexIndex(double v, uint64_t vertices, const std::string& where) {
  if (v < 0 || v >= double(vertices) || v != std::floor(v))
    throw inputError(where, vertices ? "vertex indices from 0 to " + std::to_string(vertices - 1)
                                     : std::string("no face (the file has no vertices)"), exactNumberText(v));
  return int(v);
}

/// A face's vertex indices: whole numbers below `vertices`.
std::vector<int> readFaceIndices(BodyReader& body, const Property& p, size_t n, uint64_t vertices,
                                 const std::string& where) {
  std::vector<int> idx(n);
  for (size_t k = 0; k < n; ++k) idx[k] = vertexIndex(body.scalar(p.type, where), vertices, where);
  return idx;
}

/// Reads past the n items of a list that holds no face.
void skipList(BodyReader& body, const Property& p, size_t n, const std::string& where) {
  for (size_t k = 0; k < n; ++k) body.scalar(p.type, where);
}

/// Reads list property p of a record of e: a face's vertex indices into out.faces; any
/// other list is read past.
void readList(BodyReader& body, const Element& e, const Property& p, uint64_t vertices,
              const std::string& where, PlyPolygons& out) {
  const bool face = isFaceList(e, p);
  const size_t n = listLength(body, p, where, face);
  if (face) out.faces.push_back(readFaceIndices(body, p, n, vertices, where));
  else skipList(body, p, n, where);
}

/// The columns of element e's scalar properties (none unless e holds vertices or faces),
/// added to the mesh: a pointer to the first, or null.
PlyColumn* addColumns(const Element& e, PlyPolygons& out) {
  if (e.name != "vertex" && e.name != "face") return nullptr;
  auto& columns = e.name == "vertex" ? out.mesh.vertex : out.mesh.face;
  const size_t first = columns.size();
  for (const auto& p : e.properties)
    if (p.countType.empty()) columns.push_back({p.name, PlyColumn::Type::Float, {}});
  return columns.data() + first;
}

/// Reads property p of a record of e: a list (see readList), or a scalar appended to the next
/// of `columns` (if any; the pointer moves on).
void readProperty(BodyReader& body, const Element& e, const Property& p, PlyColumn*& columns,
                  uint64_t vertices, const std::string& where, PlyPolygons& out) {
  if (!p.countType.empty()) return readList(body, e, p, vertices, where, out);
  const double v = body.scalar(p.type, where);
  if (columns) (columns++)->values.push_back(v);
}

/// Reads record i of element e; its scalars go to `columns` (if any), in order.
void readRecord(BodyReader& body, const Element& e, uint64_t i, PlyColumn* columns,
                uint64_t vertices, const std::string& path, PlyPolygons& out) {
  const std::string record = path + ": " + e.name + " " + std::to_string(i);
  for (const auto& p : e.properties) readProperty(body, e, p, columns, vertices, record + ": " + p.name, out);
}

/// At most one vertex_indices list per element.
void checkFaceLists(const Element& e, const std::string& path) {
  int faceLists = 0;
  for (const auto& p : e.properties) faceLists += isFaceList(e, p);
  if (faceLists > 1) throw inputError(path + ": element face", "one vertex_indices list", "two");
}

/// Reads the records of element e; the scalars of vertices and faces go to their columns.
void readElement(BodyReader& body, const Element& e, uint64_t vertices, const std::string& path,
                 PlyPolygons& out) {
  checkFaceLists(e, path);
  PlyColumn* columns = addColumns(e, out);
  for (uint64_t i = 0; i < e.count; ++i) readRecord(body, e, i, columns, vertices, path, out);
}

/// The vertex count the header announces (0 without a vertex element).
uint64_t vertexCount(const Header& h) {
  uint64_t vertices = 0;
  for (const auto& e : h.elements)
    if (e.name == "vertex") vertices = e.count;
  return vertices;
}

/// Every element's records, in the header's order.
PlyPolygons readBody(const std::string& bytes, const Header& h, const std::string& path) {
  PlyPolygons out;
  out.mesh.comments = h.comments;
  const uint64_t vertices = vertexCount(h);
  BodyReader body(bytes, h);
  for (const auto& e : h.elements) readElement(body, e, vertices, path, out);
  return out;
}

/// A PLY file starts with its magic line.
void checkMagic(const std::string& head, const std::string& path) {
  if (head.compare(0, 4, "ply\n") != 0 && head.compare(0, 5, "ply\r\n") != 0)
    throw inputError(path, "a PLY file", "no 'ply' magic line");
}

/// Face f as a triangle; any other polygon is an error.
std::array<int, 3> triangle(const std::vector<int>& face, size_t f, const std::string& path) {
  if (face.size() != 3)
    throw inputError(path + ": face " + std::to_string(f), "triangle faces",
                     "a face with " + std::to_string(face.size()) + " vertices");
  return {face[0], face[1], face[2]};
}

/// The file's bytes, its magic checked before the rest is read (`what` names the file expected).
std::string readPlyBytes(const std::string& path, const std::string& what) {
  return readInputFile(path, what, kMaxInputFileBytes, false,
                       [&](const std::string& head) { checkMagic(head, path); });
}

/// The header's format is binary_little_endian, as results are written.
void checkResultFormat(const Header& header, const std::string& path) {
  if (header.format != Format::BinaryLittleEndian)
    throw inputError(path, "binary_little_endian PLY",
                     std::string("format ") + (header.format == Format::Ascii ? "ascii" : "binary_big_endian"));
}

/// The faces read, each a triangle.
std::vector<std::array<int, 3>> triangles(const std::vector<std::vector<int>>& faces, const std::string& path) {
  std::vector<std::array<int, 3>> out;
  for (size_t f = 0; f < faces.size(); ++f) out.push_back(triangle(faces[f], f, path));
  return out;
}

}  // namespace

const PlyColumn* findColumn(const std::vector<PlyColumn>& columns, const std::string& name) {
  for (const auto& c : columns)
    if (c.name == name) return &c;
  return nullptr;
}

PlyPolygons readPlyPolygons(const std::string& path) {
  const std::string bytes = readPlyBytes(path, "a PLY file");
  return readBody(bytes, parseHeader(bytes, path), path);
}

PlyMesh readPly(const std::string& path) {
  const std::string bytes = readPlyBytes(path, "a readable PLY file");
  const Header header = parseHeader(bytes, path);
  checkResultFormat(header, path);
  PlyPolygons read = readBody(bytes, header, path);
  read.mesh.faces = triangles(read.faces, path);
  return std::move(read.mesh);
}

}  // namespace rad
