// Planar pieces ▸ elements ▸ seams: which element edges lie along a piece's contact lines.
#include "mesh/seams.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

namespace rad::meshing {
namespace {

/// A point lies on a line when it is this close to it, relative to the line's length: the
/// line's own points, made by splitting it in the plane's frame and lifting them back, lie
/// within rounding of it; other points of a Delaunay mesh lie a good share of an element
/// away.
constexpr double kOnLine = 1e-9;

/// The lines of a piece in its frame.
struct Line2 {
  glm::dvec2 a{0.0}, b{0.0};
};

/// Whether q lies on the segment from a to b (within kOnLine of its length).
bool onSegment(const Line2& line, const glm::dvec2& q) {
  const glm::dvec2 d = line.b - line.a;
  const double len2 = glm::dot(d, d);
  if (!(len2 > 0)) return false;
  const double t = glm::dot(q - line.a, d) / len2;
  if (t < -kOnLine || t > 1 + kOnLine) return false;
  const glm::dvec2 off = q - (line.a + t * d);
  return glm::dot(off, off) <= kOnLine * kOnLine * len2;
}

}  // namespace

EdgeSet seamEdges(const PointTable& table, const Piece& piece,
                  const std::vector<std::array<int, 3>>& triangles) {
  EdgeSet seams;
  if (piece.lines.empty()) return seams;
  std::vector<Line2> lines;
  for (const auto& [p, q] : piece.lines)
    lines.push_back({piece.frame.project(table[p]), piece.frame.project(table[q])});
  // Which lines each point of the elements lies on.
  std::map<int, std::vector<int>> linesAt;
  for (const auto& t : triangles)
    for (int id : t) {
      if (linesAt.count(id)) continue;
      std::vector<int>& on = linesAt[id];
      const glm::dvec2 q = piece.frame.project(table[id]);
      for (size_t k = 0; k < lines.size(); ++k)
        if (onSegment(lines[k], q)) on.push_back(int(k));
    }
  // An edge whose two ends lie on one line runs along it.
  auto shareLine = [](const std::vector<int>& x, const std::vector<int>& y) {
    return std::any_of(x.begin(), x.end(), [&](int k) { return std::find(y.begin(), y.end(), k) != y.end(); });
  };
  for (const auto& t : triangles)
    for (int i = 0; i < 3; ++i) {
      const int a = t[size_t(i)], b = t[size_t((i + 1) % 3)];
      if (shareLine(linesAt[a], linesAt[b])) seams.insert(std::minmax(a, b));
    }
  return seams;
}

}  // namespace rad::meshing
