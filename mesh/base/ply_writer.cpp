#include "mesh/base/ply_writer.h"

#include <cstring>
#include <ostream>
#include <vector>

#include "mesh/base/error.h"
#include "mesh/base/output_file.h"

namespace rad {
namespace {

/// The PLY name of a column type.
const char* typeName(PlyColumn::Type t) {
  switch (t) {
    case PlyColumn::Type::Float: return "float";
    case PlyColumn::Type::Int: return "int";
    default: return "uchar";
  }
}

/// The body's bytes, gathered and written a megabyte at a time (a stream's write per value
/// took as long as the rest of the output); flush() writes what is left.
class BodyWriter {
 public:
  explicit BodyWriter(std::ostream& out) : out_(out) { bytes_.reserve(kChunk + 64); }
  BodyWriter(const BodyWriter&) = delete;
  BodyWriter& operator=(const BodyWriter&) = delete;

  /// Appends the value's bytes.
  template <class T>
  void put(T value) {
    static_assert(sizeof(T) <= 4);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));  // x86-64 and every target we build for are little-endian
    bytes_.insert(bytes_.end(), bytes, bytes + sizeof(T));
    if (bytes_.size() >= kChunk) flush();
  }
  void flush() {
    out_.write(bytes_.data(), std::streamsize(bytes_.size()));
    bytes_.clear();
  }

 private:
  static constexpr size_t kChunk = size_t(1) << 20;
  std::ostream& out_;
  std::vector<char> bytes_;
};

/// Writes v as a value of type t.
void putValue(BodyWriter& out, PlyColumn::Type t, double v) {
  switch (t) {
    case PlyColumn::Type::Float: out.put(float(v)); break;
    case PlyColumn::Type::Int: out.put(int32_t(v)); break;
    default: out.put(uint8_t(v)); break;
  }
}

/// Every column holds n values.
void checkColumns(const std::vector<PlyColumn>& columns, size_t n) {
  for (const auto& c : columns) RAD_CHECK_EQ(c.values.size(), n);
}

/// A header line "property <type> <name>" per column.
void writeProperties(std::ostream& out, const std::vector<PlyColumn>& columns) {
  for (const auto& c : columns) out << "property " << typeName(c.type) << " " << c.name << "\n";
}

/// The header: the comments, then nv vertices and the triangles with their columns.
void writeHeader(std::ostream& out, const PlyMesh& mesh, size_t nv) {
  out << "ply\nformat binary_little_endian 1.0\n";
  for (const auto& c : mesh.comments) out << "comment " << c << "\n";
  out << "element vertex " << nv << "\n";
  writeProperties(out, mesh.vertex);
  out << "element face " << mesh.faces.size() << "\n";
  out << "property list uchar int vertex_indices\n";
  writeProperties(out, mesh.face);
  out << "end_header\n";
}

/// Record i: its value in each column.
void writeRecord(BodyWriter& out, const std::vector<PlyColumn>& columns, size_t i) {
  for (const auto& c : columns) putValue(out, c.type, c.values[i]);
}

/// Triangle f's record: its corner count (3), its corners, then its columns.
void writeTriangle(BodyWriter& out, const PlyMesh& mesh, size_t f) {
  out.put(uint8_t(3));
  for (int k = 0; k < 3; ++k) out.put(int32_t(mesh.faces[f][k]));
  writeRecord(out, mesh.face, f);
}

/// The records: each vertex's columns, then each triangle's corners and columns.
void writeBody(std::ostream& stream, const PlyMesh& mesh, size_t nv) {
  BodyWriter out(stream);
  for (size_t i = 0; i < nv; ++i) writeRecord(out, mesh.vertex, i);
  for (size_t f = 0; f < mesh.faces.size(); ++f) writeTriangle(out, mesh, f);
  out.flush();
}

/// The vertices: the length of the vertex columns (0 without any).
size_t vertexCount(const PlyMesh& mesh) {
  return mesh.vertex.empty() ? 0 : mesh.vertex[0].values.size();
}

}  // namespace

void writePly(const std::string& path, const PlyMesh& mesh) {
  const size_t nv = vertexCount(mesh);
  checkColumns(mesh.vertex, nv);
  checkColumns(mesh.face, mesh.faces.size());
  writeFileAtomically(path, [&](std::ostream& out) {
    writeHeader(out, mesh, nv);
    writeBody(out, mesh, nv);
  });
}

}  // namespace rad
