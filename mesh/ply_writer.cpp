#include "mesh/ply_writer.h"

#include <cstring>
#include <ostream>

#include "mesh/error.h"
#include "mesh/output_file.h"

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

/// Writes the value's bytes.
template <class T>
void put(std::ostream& out, T value) {
  static_assert(sizeof(T) <= 4);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // x86-64 and every target we build for are little-endian
  out.write(bytes, sizeof(T));
}

/// Writes v as a value of type t.
void putValue(std::ostream& out, PlyColumn::Type t, double v) {
  switch (t) {
    case PlyColumn::Type::Float: put(out, float(v)); break;
    case PlyColumn::Type::Int: put(out, int32_t(v)); break;
    default: put(out, uint8_t(v)); break;
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
void writeRecord(std::ostream& out, const std::vector<PlyColumn>& columns, size_t i) {
  for (const auto& c : columns) putValue(out, c.type, c.values[i]);
}

/// Triangle f's record: its corner count (3), its corners, then its columns.
void writeTriangle(std::ostream& out, const PlyMesh& mesh, size_t f) {
  put(out, uint8_t(3));
  for (int k = 0; k < 3; ++k) put(out, int32_t(mesh.faces[f][k]));
  writeRecord(out, mesh.face, f);
}

/// The records: each vertex's columns, then each triangle's corners and columns.
void writeBody(std::ostream& out, const PlyMesh& mesh, size_t nv) {
  for (size_t i = 0; i < nv; ++i) writeRecord(out, mesh.vertex, i);
  for (size_t f = 0; f < mesh.faces.size(); ++f) writeTriangle(out, mesh, f);
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
