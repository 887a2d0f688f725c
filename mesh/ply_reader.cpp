#include "mesh/ply_reader.h"

#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "mesh/error.h"

namespace rad {
namespace {

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

double readScalar(std::istream& in, const std::string& t) {
  char b[8];
  in.read(b, typeSize(t));
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

struct Property {
  std::string name, type, countType;  // countType set for lists
};
struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> properties;
};

}  // namespace

const PlyColumn* findColumn(const std::vector<PlyColumn>& columns, const std::string& name) {
  for (const auto& c : columns)
    if (c.name == name) return &c;
  return nullptr;
}

PlyMesh readPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw inputError(path, "a readable PLY file", "no such file");
  std::string line;
  if (!std::getline(in, line) || line != "ply") throw inputError(path, "a PLY file", "no 'ply' magic line");
  PlyMesh mesh;
  std::vector<Element> elements;
  bool binaryLE = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      std::string format;
      words >> format;
      binaryLE = format == "binary_little_endian";
      if (!binaryLE) throw inputError(path, "binary_little_endian PLY", "format " + format);
    } else if (word == "comment") {
      mesh.comments.push_back(line.size() > 8 ? line.substr(8) : "");
    } else if (word == "element") {
      Element e;
      words >> e.name >> e.count;
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) throw inputError(path, "an element before its properties", line);
      Property p;
      words >> p.type;
      if (p.type == "list") words >> p.countType >> p.type;
      words >> p.name;
      if (!typeSize(p.type) || (!p.countType.empty() && !typeSize(p.countType)))
        throw inputError(path, "PLY scalar types", "'" + line + "'");
      elements.back().properties.push_back(p);
    } else if (word == "end_header") {
      break;
    }
  }
  if (!binaryLE) throw inputError(path, "a PLY header with a format line and end_header", "none");
  for (const auto& e : elements) {
    bool isVertex = e.name == "vertex", isFace = e.name == "face";
    auto& columns = isVertex ? mesh.vertex : mesh.face;
    // Scalar properties of the vertex and face elements become columns; others are skipped.
    const size_t first = columns.size();
    if (isVertex || isFace)
      for (const auto& p : e.properties)
        if (p.countType.empty()) columns.push_back({p.name, PlyColumn::Type::Float, {}});
    for (size_t i = 0; i < e.count; ++i) {
      size_t c = 0;
      for (const auto& p : e.properties) {
        if (p.countType.empty()) {
          double v = readScalar(in, p.type);
          if (isVertex || isFace) columns[first + c++].values.push_back(v);
          continue;
        }
        size_t n = size_t(readScalar(in, p.countType));
        std::vector<int> idx(n);
        for (auto& x : idx) x = int(readScalar(in, p.type));
        if (isFace && p.name == "vertex_indices") {
          if (n != 3) throw inputError(path, "triangle faces", "a face with " + std::to_string(n) + " vertices");
          mesh.faces.push_back({idx[0], idx[1], idx[2]});
        }
      }
      if (!in) throw inputError(path, "the " + std::to_string(e.count) + " " + e.name + " records the header announces", "a truncated file");
    }
  }
  size_t nv = mesh.vertex.empty() ? 0 : mesh.vertex[0].values.size();
  for (const auto& f : mesh.faces)
    for (int v : f)
      if (v < 0 || size_t(v) >= nv)
        throw inputError(path, "vertex indices below " + std::to_string(nv), "index " + std::to_string(v));
  return mesh;
}

}  // namespace rad
