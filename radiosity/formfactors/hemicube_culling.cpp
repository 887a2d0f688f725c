#include "radiosity/formfactors/hemicube_culling.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace rad {
namespace {

/// Relative round-off allowed in a box's height above the base plane.
constexpr double kBaseRoundOff = 1e-12;
/// Pixels of room around a box's projection: the raster snaps vertices to 1/256 pixel (so
/// moves them by up to 1/512 each way), and the corners' float local coordinates move their
/// projections by ~1e-7 × (scene size / distance) × R/2 pixels, a few thousandths of a pixel
/// for what lies beyond a cube's near occluders.
constexpr double kSnapRoom = 1.0 / 8;

/// The box's eight corners in the cube's local coordinates.
std::array<glm::dvec3, 8> localCorners(const HemicubeFrame& frame, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 centre = frame.local(0.5 * (lo + hi)), half = 0.5 * (hi - lo);
  // The box's half edges along x, y, z, in local coordinates.
  const glm::dvec3 ex = half.x * glm::dvec3(frame.u.x, frame.v.x, frame.n.x);
  const glm::dvec3 ey = half.y * glm::dvec3(frame.u.y, frame.v.y, frame.n.y);
  const glm::dvec3 ez = half.z * glm::dvec3(frame.u.z, frame.v.z, frame.n.z);
  std::array<glm::dvec3, 8> corners;
  for (int k = 0; k < 8; ++k)
    corners[size_t(k)] = centre + (k & 1 ? ex : -ex) + (k & 2 ? ey : -ey) + (k & 4 ? ez : -ez);
  return corners;
}

/// The box's eight corners on face f: their clip-space x, y and w (faceClip), and the
/// least and greatest w.
struct FaceCorners {
  std::array<double, 8> x, y, w;
  double wMin = INFINITY, wMax = -INFINITY;

  FaceCorners(int f, const std::array<glm::dvec3, 8>& corners, double near) {
    for (size_t k = 0; k < 8; ++k) {
      const glm::dvec4 clip = faceClip(f, corners[k].x, corners[k].y, corners[k].z, near);
      x[k] = clip.x, y[k] = clip.y, w[k] = clip.w;
      wMin = std::min(wMin, clip.w), wMax = std::max(wMax, clip.w);
    }
  }
};

/// The pixels whose centre lies in the window interval [lo, hi] widened by kSnapRoom each
/// way, within [0, size - 1].
std::pair<int, int> pixelSpan(double lo, double hi, int size) {
  // Both clamped to [-1, size + 1] (size ≤ raster::kMaxSize), shifted so that truncation
  // rounds down: floor(x) = int(x + kShift) - kShift, ceil(x) = -floor(-x).
  constexpr int kShift = 1 << 16;
  lo = std::max(lo, -1.0) - kSnapRoom, hi = std::min(hi, size + 1.0) + kSnapRoom;
  const int first = kShift - int(kShift + 0.5 - lo), last = int(hi - 0.5 + kShift) - kShift;
  return {std::max(first, 0), std::min(last, size - 1)};
}

/// Whether the box, wholly beyond the face's near plane (c.wMin > near), is hidden on face f:
/// every pixel its projection may cover holds a depth greater than its nearest corner's.
bool hiddenOnFace(int f, const FaceCorners& c, const HemicubeDepths& depths) {
  const int width = depths.resolution, height = f == 0 ? width : width / 2;
  double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
  for (size_t k = 0; k < 8; ++k) {
    const double r = 1 / c.w[k];
    xMin = std::min(xMin, c.x[k] * r), xMax = std::max(xMax, c.x[k] * r);
    yMin = std::min(yMin, c.y[k] * r), yMax = std::max(yMax, c.y[k] * r);
  }
  const auto [x0, x1] = pixelSpan((xMin + 1) * 0.5 * width, (xMax + 1) * 0.5 * width, width);
  const auto [y0, y1] = pixelSpan((yMin + 1) * 0.5 * height, (yMax + 1) * 0.5 * height, height);
  if (x0 > x1 || y0 > y1) return true;  // it misses the face
  const float depth = float(depths.near / c.wMin * (1 + kHiddenDepthMargin));
  return depths.pyramids[size_t(f)].covers({x0, y0, x1, y1}, depth);
}

}  // namespace

bool boxBelowBase(const HemicubeFrame& frame, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 centre = 0.5 * (lo + hi) - frame.eye, half = 0.5 * (hi - lo);
  const double top = glm::dot(centre, frame.n) + glm::dot(half, glm::abs(frame.n));
  const double scale = glm::dot(glm::abs(centre), glm::dvec3(1.0)) + glm::dot(half, glm::dvec3(1.0));
  return top < -kBaseRoundOff * scale;
}

bool boxHidden(const HemicubeFrame& frame, const glm::dvec3& lo, const glm::dvec3& hi,
               const HemicubeDepths& depths) {
  const std::array<glm::dvec3, 8> corners = localCorners(frame, lo, hi);
  uint32_t shared = 0;  // the planes all corners are outside of, once needed
  bool sharedKnown = false;
  for (int f = 0; f < 5; ++f) {
    const FaceCorners c(f, corners, depths.near);
    if (c.wMax < depths.near) continue;  // wholly before the near plane: the face draws none of it
    if (c.wMin > depths.near) {
      if (!hiddenOnFace(f, c, depths)) return false;
      continue;
    }
    // Reaching the near plane: shown unless wholly beyond one of the face's other planes.
    if (!sharedKnown) {
      shared = ~0u;
      for (const glm::dvec3& p : corners) shared &= outsidePlanes(p.x, p.y, p.z);
      sharedKnown = true;
    }
    if (((shared >> (5 * f)) & 31u) == 0) return false;
  }
  return true;
}

}  // namespace rad
