#pragma once
// A generated building for the hemicube's tests and benchmarks: rooms on a grid, each closed
// by a floor, a ceiling and four walls with a doorway in each, the walls `wall` thick between
// rooms, every rectangle meshed into a grid of right triangles. Only the faces towards the
// rooms (and the doorways' jambs, lintel and threshold) exist. Metres, y up.
//
//   z ^  +------+-- --+------+      one row of three rooms seen from above: each wall has
//     |  |      |     |      |      a doorway (the gaps); walls between rooms are shared
//     |         |           |
//     |  |      |     |      |
//     |  +------+-- --+------+
//     +------------------------> x
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "radiosity/formfactors/hemicube.h"

namespace rad::test {

struct RoomGrid {
  int roomsX = 3, roomsZ = 1;  ///< rooms along x and z
  double room = 4;             ///< the grid's cell (wall centre to wall centre)
  double height = 2.5, wall = 0.2, doorWidth = 0.9, doorHeight = 2.0;
  double edge = 0.25;  ///< the triangles' legs (at most)

  /// The centre of room (i, k) at height y.
  glm::dvec3 centre(int i, int k, double y) const { return {(i + 0.5) * room, y, (k + 0.5) * room}; }
};

/// Adds the axis-aligned rectangle [lo, hi] (lo[axis] == hi[axis]) facing `sign` along
/// `axis`, as a grid of cells of at most `edge`, two triangles each.
inline void addRectangle(HemicubeGeometry& g, glm::dvec3 lo, glm::dvec3 hi, int axis, int sign, double edge) {
  // cross(e_p, e_q) = e_axis for the cyclic successors p, q: swap them to face the other way.
  int p = (axis + 1) % 3, q = (axis + 2) % 3;
  if (sign < 0) std::swap(p, q);
  const int np = std::max(1, int(std::ceil((hi[p] - lo[p]) / edge - 1e-9)));
  const int nq = std::max(1, int(std::ceil((hi[q] - lo[q]) / edge - 1e-9)));
  auto point = [&](int i, int j) {
    glm::dvec3 x = lo;
    x[p] = lo[p] + (hi[p] - lo[p]) * i / np;
    x[q] = lo[q] + (hi[q] - lo[q]) * j / nq;
    return x;
  };
  const uint32_t base = uint32_t(g.positions.size());
  for (int j = 0; j <= nq; ++j)
    for (int i = 0; i <= np; ++i) g.positions.push_back(point(i, j));
  glm::dvec3 normal(0.0);
  normal[axis] = sign;
  auto at = [&](int i, int j) { return base + uint32_t(j * (np + 1) + i); };
  for (int j = 0; j < nq; ++j)
    for (int i = 0; i < np; ++i) {
      g.indices.insert(g.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      g.indices.insert(g.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      g.normals.insert(g.normals.end(), {normal, normal});
    }
}

/// A wall's inner face at `at` along `axis` (0: x, 2: z) facing `sign`, spanning [a, b]
/// along the other horizontal axis, with a doorway in its middle.
inline void addWallFace(HemicubeGeometry& g, const RoomGrid& r, int axis, double at, int sign, double a, double b) {
  const int along = 2 - axis;
  const double mid = 0.5 * (a + b), d0 = mid - 0.5 * r.doorWidth, d1 = mid + 0.5 * r.doorWidth;
  auto piece = [&](double s0, double s1, double y0, double y1) {
    glm::dvec3 lo(0.0, y0, 0.0), hi(0.0, y1, 0.0);
    lo[axis] = hi[axis] = at;
    lo[along] = s0, hi[along] = s1;
    addRectangle(g, lo, hi, axis, sign, r.edge);
  };
  piece(a, d0, 0, r.height);
  piece(d1, b, 0, r.height);
  piece(d0, d1, r.doorHeight, r.height);
}

/// The doorway through the wall on the grid line `line` along `axis`, in the cell spanning
/// [a, b] along the other axis: two jambs, the lintel and the threshold.
inline void addDoorway(HemicubeGeometry& g, const RoomGrid& r, int axis, double line, double a, double b) {
  const int along = 2 - axis;
  const double mid = 0.5 * (a + b), d0 = mid - 0.5 * r.doorWidth, d1 = mid + 0.5 * r.doorWidth;
  const double w0 = line - 0.5 * r.wall, w1 = line + 0.5 * r.wall;
  auto box = [&](double s0, double s1, double y0, double y1) {
    glm::dvec3 lo(0.0, y0, 0.0), hi(0.0, y1, 0.0);
    lo[axis] = w0, hi[axis] = w1, lo[along] = s0, hi[along] = s1;
    return std::pair(lo, hi);
  };
  auto [jamb0lo, jamb0hi] = box(d0, d0, 0, r.doorHeight);
  addRectangle(g, jamb0lo, jamb0hi, along, +1, r.edge);
  auto [jamb1lo, jamb1hi] = box(d1, d1, 0, r.doorHeight);
  addRectangle(g, jamb1lo, jamb1hi, along, -1, r.edge);
  auto [lintelLo, lintelHi] = box(d0, d1, r.doorHeight, r.doorHeight);
  addRectangle(g, lintelLo, lintelHi, 1, -1, r.edge);
  auto [sillLo, sillHi] = box(d0, d1, 0, 0);
  addRectangle(g, sillLo, sillHi, 1, +1, r.edge);
}

/// The building's triangles, each facing into its room (or doorway).
inline HemicubeGeometry roomGrid(const RoomGrid& r) {
  HemicubeGeometry g;
  const double h = 0.5 * r.wall;
  for (int k = 0; k < r.roomsZ; ++k)
    for (int i = 0; i < r.roomsX; ++i) {
      const double x0 = i * r.room + h, x1 = (i + 1) * r.room - h;
      const double z0 = k * r.room + h, z1 = (k + 1) * r.room - h;
      addRectangle(g, {x0, 0, z0}, {x1, 0, z1}, 1, +1, r.edge);                  // floor
      addRectangle(g, {x0, r.height, z0}, {x1, r.height, z1}, 1, -1, r.edge);    // ceiling
      addWallFace(g, r, 0, x0, +1, z0, z1);
      addWallFace(g, r, 0, x1, -1, z0, z1);
      addWallFace(g, r, 2, z0, +1, x0, x1);
      addWallFace(g, r, 2, z1, -1, x0, x1);
    }
  // Each grid line's walls, one doorway per room side.
  for (int k = 0; k < r.roomsZ; ++k)
    for (int i = 0; i <= r.roomsX; ++i) addDoorway(g, r, 0, i * r.room, k * r.room, (k + 1) * r.room);
  for (int k = 0; k <= r.roomsZ; ++k)
    for (int i = 0; i < r.roomsX; ++i) addDoorway(g, r, 2, k * r.room, i * r.room, (i + 1) * r.room);
  return g;
}

}  // namespace rad::test
