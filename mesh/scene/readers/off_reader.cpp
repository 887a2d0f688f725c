#include "mesh/scene/readers/off_reader.h"

#include <cmath>
#include <set>
#include <sstream>

#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/base/number_text.h"
#include "mesh/base/ply_reader.h"

namespace rad {
namespace {

/// Words of an OFF file, '#' comments left out, each with its line for messages.
class OffWords {
 public:
  OffWords(const std::string& text, const std::string& path) : in_(text), path_(path) {}
  std::string where() const { return path_ + ": line " + std::to_string(line_); }
  bool next(std::string& word) {
    while (!(words_ >> word))
      if (!nextLine()) return false;
    return true;
  }
  double number(const char* what) {
    if (!next(word_)) throw inputError(where(), what, "the end of the file (a truncated file)");
    double v;
    if (!finiteNumber(word_, v)) throw inputError(where(), what, "'" + word_ + "'");
    return v;
  }
  uint64_t count(const char* what, uint64_t most) {
    const double v = number(what);
    if (v < 0 || v != std::floor(v) || v > double(most))
      throw inputError(where(), std::string(what) + " from 0 to " + std::to_string(most), "'" + word_ + "'");
    return uint64_t(v);
  }
  void skipLine() { words_.str(""), words_.clear(); }

 private:
  /// Moves on to the next line's words, its comment left out; false at the end.
  bool nextLine() {
    std::string line;
    if (!std::getline(in_, line)) return false;
    ++line_;
    words_.clear();
    words_.str(line.substr(0, line.find('#')));
    return true;
  }

  std::istringstream in_, words_;
  std::string path_, word_;
  int line_ = 0;
};

/// The keyword: OFF, with the optional prefixes for texture coordinates, colours and normals
/// after each vertex (skipped); 4OFF and nOFF (homogeneous, n-dimensional) are not 3D meshes.
void checkOffKeyword(OffWords& words) {
  std::string magic;
  static const std::set<std::string> keywords = {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCOFF", "STNOFF", "STCNOFF"};
  if (!words.next(magic) || !keywords.count(magic))
    throw inputError(words.where(), "the 'OFF' keyword (or COFF, NOFF, CNOFF, STOFF, STCOFF, STNOFF, STCNOFF)",
                     magic.empty() ? "nothing" : "'" + magic + "'");
}

/// One vertex line: its position.
glm::dvec3 readOffPoint(OffWords& words) {
  const glm::dvec3 p = {words.number("a vertex x"), words.number("a vertex y"), words.number("a vertex z")};
  words.skipLine();  // colours or normals after the position are not ours
  return p;
}

/// The vertices' positions, one a line.
std::vector<glm::dvec3> readOffPoints(OffWords& words, uint64_t vertices) {
  std::vector<glm::dvec3> points(vertices);
  for (auto& p : points) p = readOffPoint(words);
  return points;
}

/// One face line: its vertex count and the indices of its vertices among `points`.
Polygon readOffFace(OffWords& words, const std::vector<glm::dvec3>& points) {
  const uint64_t n = words.count("a face's vertex count", kMaxPlyFaceVertices);
  if (points.empty() && n > 0) throw inputError(words.where(), "a face of the file's vertices", "a file without vertices");
  Polygon face;
  for (uint64_t k = 0; k < n; ++k) face.outer.push_back(points[words.count("a vertex index", points.size() - 1)]);
  words.skipLine();  // a face colour may follow
  return face;
}

/// The `faces` face lines, of vertices among `points`, as one group.
MeshFileGroup readOffFaces(OffWords& words, uint64_t faces, const std::vector<glm::dvec3>& points) {
  MeshFileGroup group;
  for (uint64_t f = 0; f < faces; ++f) group.faces.push_back(readOffFace(words, points));
  return group;
}

/// The vertex and face counts of an OFF file.
struct OffCounts {
  uint64_t vertices, faces;
};

/// The vertex, face and edge counts, checked against the file's size (`bytes`).
OffCounts readOffCounts(OffWords& words, size_t bytes) {
  // Every vertex takes at least 6 bytes ("0 0 0\n"), every face 8 ("3 0 1 2\n").
  const uint64_t vertices = words.count("a vertex count", bytes / 6);
  const uint64_t faces = words.count("a face count", bytes / 8);
  words.count("an edge count", UINT64_MAX >> 12);
  return {vertices, faces};
}

}  // namespace

std::vector<MeshFileGroup> readOffFile(const std::string& path) {
  const std::string text = readInputFile(path, "an OFF file");
  OffWords words(text, path);
  checkOffKeyword(words);
  const OffCounts counts = readOffCounts(words, text.size());
  return {readOffFaces(words, counts.faces, readOffPoints(words, counts.vertices))};
}

}  // namespace rad
