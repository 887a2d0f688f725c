#pragma once
// A hemicube's frame and its five faces: local coordinates (a, b, c) along (u, v, n) from
// the eye, each face's clip space, and the frustum planes a point lies outside of. Shared by
// the hemicube (per vertex, in float) and its culling (per box corner, in double).
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace rad {

struct HemicubeFrame {
  glm::dvec3 eye, u, v, n;

  /// The frame at x + eyeOffset·n with unit normal n, turned about n by 2π·rotation.
  static HemicubeFrame make(const glm::dvec3& x, const glm::dvec3& n, double rotation, double eyeOffset);
  /// Local coordinates (a, b, c) of world point p.
  glm::dvec3 local(const glm::dvec3& p) const {
    const glm::dvec3 d = p - eye;
    return {d.x * u.x + d.y * u.y + d.z * u.z, d.x * v.x + d.y * v.y + d.z * v.z, d.x * n.x + d.y * n.y + d.z * n.z};
  }
};

/// Face f's clip-space coordinates of a point with local coordinates (a, b, c). Face 0 is the
/// top, 1–4 the sides along +u, -u, +v, -v. Depth is reversed with z in [0, w] (z = near, so
/// depth = near/distance, test GREATER): a 32-bit float then resolves distance to ~1e-7
/// relative at every range, so the near plane can sit very close. Side faces show only the
/// upper half (c ≥ 0): y maps c ∈ [0, w] onto [-w, w].
template <class T>
inline glm::vec<4, T> faceClip(int f, T a, T b, T c, T near) {
  switch (f) {
    case 0: return {a, b, near, c};
    case 1: return {b, 2 * c - a, near, a};
    case 2: return {-b, 2 * c + a, near, -a};
    case 3: return {-a, 2 * c - b, near, b};
    default: return {a, 2 * c + b, near, -b};
  }
}

/// The local direction (a, b, c) that face f shows at normalised device coordinates (x, y)
/// (faceClip's inverse up to scale): the top face's (x, y, 1), a side face's at unit
/// distance along its axis.
template <class T>
inline glm::vec<3, T> faceDirection(int f, T x, T y) {
  const T c = (y + 1) / 2;
  switch (f) {
    case 0: return {x, y, 1};
    case 1: return {1, x, c};
    case 2: return {-1, -x, c};
    case 3: return {-x, 1, c};
    default: return {x, -1, c};
  }
}

/// The frustum planes of the five faces that local point (a, b, c) lies strictly outside of:
/// bits 5f..5f+4 for face f. A triangle (or box) whose corners share a bit of face f shows
/// nothing on it (its projection lies beyond that edge of the face, or behind the eye), so
/// the face need not draw it. Face f's planes are those of faceClip(f): |x| ≤ w, |y| ≤ w,
/// w > 0. Bit 4 (the top face's w > 0) is c > 0: the base plane.
template <class T>
inline uint32_t outsidePlanes(T a, T b, T c) {
  auto face = [](T x, T w, T c) {  // a side face: |x| ≤ w, 0 ≤ c ≤ w
    return uint32_t(x > w) | uint32_t(-x > w) << 1 | uint32_t(c > w) << 2 | uint32_t(c < 0) << 3 |
           uint32_t(w <= 0) << 4;
  };
  const uint32_t top = uint32_t(a > c) | uint32_t(-a > c) << 1 | uint32_t(b > c) << 2 |
                       uint32_t(-b > c) << 3 | uint32_t(c <= 0) << 4;
  return top | face(b, a, c) << 5 | face(b, -a, c) << 10 | face(a, b, c) << 15 | face(a, -b, c) << 20;
}

/// The bit of outsidePlanes() saying a point is on or below the base plane.
constexpr uint32_t kBelowBase = 16u;

}  // namespace rad
