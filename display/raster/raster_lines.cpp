// drawLines: segments clipped in homogeneous space and to the viewport, then a DDA on pixel
// centres along the major axis.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "display/raster/raster.h"
#include "display/raster/raster_internal.h"

namespace raster {
namespace {

using detail::PixelRange;

/// Clips segment (a, b) in homogeneous space against the near plane (z >= -w, or z >= 0 for
/// the [0, 1] convention) and the far plane; false if nothing is left in front of the eye.
bool clipNearFar(glm::dvec4& a, glm::dvec4& b, bool zeroToOne) {
  // Signed distances to the near and far planes (inside >= 0).
  auto nearD = [&](const glm::dvec4& v) { return zeroToOne ? v.z : v.z + v.w; };
  auto farD = [](const glm::dvec4& v) { return v.w - v.z; };
  for (int plane = 0; plane < 2; ++plane) {
    const double da = plane == 0 ? nearD(a) : farD(a), db = plane == 0 ? nearD(b) : farD(b);
    if (da < 0 && db < 0) return false;
    if (da < 0) a = a + (b - a) * (da / (da - db));
    else if (db < 0) b = b + (a - b) * (db / (db - da));
  }
  return !(a.w <= 0 || b.w <= 0);
}

/// Clip space -> window (x_w, y_w, depth) of a W x H target.
glm::dvec3 toWindow(const glm::dvec4& v, int W, int H, bool zeroToOne) {
  const glm::dvec3 n = glm::dvec3(v) / v.w;
  return glm::dvec3((n.x + 1) * 0.5 * W, (n.y + 1) * 0.5 * H, zeroToOne ? n.z : (n.z + 1) * 0.5);
}

/// One Liang-Barsky boundary, p*t <= q: narrows [t0, t1]; false if the segment is parallel to
/// the boundary and outside it.
bool narrowToBoundary(double p, double q, double& t0, double& t1) {
  if (p == 0) return !(q < 0);
  const double r = q / p;
  if (p < 0) t0 = std::max(t0, r);
  else t1 = std::min(t1, r);
  return true;
}

/// Liang-Barsky: the range [t0, t1] of t where p0 + t*d, t in [0, 1], lies in the viewport
/// [0, W] x [0, H]; false if the segment misses it.
bool clipToViewport(const glm::dvec3& p0, const glm::dvec3& d, int W, int H, double& t0,
                    double& t1) {
  t0 = 0, t1 = 1;
  bool visible = true;
  const double pq[4][2] = {{-d.x, p0.x}, {d.x, W - p0.x}, {-d.y, p0.y}, {d.y, H - p0.y}};
  for (const auto& e : pq)
    if (!narrowToBoundary(e[0], e[1], t0, t1)) visible = false;
  return visible && !(t0 > t1);
}

// The fragment stage of drawLines: scissor, depth bias, depth test, writes.
struct LineFragments {
  Target& target;
  const State& state;
  PixelRange range;  // viewport & scissor
  glm::vec4 color;
  float depthBias;
  bool less, writeColor, countHits;

  /// Whether pixel (x, y) may be written.
  bool inside(int x, int y) const {
    return x >= range.x0 && x <= range.x1 && y >= range.y0 && y <= range.y1;
  }
  /// The fragment at pixel (x, y) with window depth z, moved toward the viewer by the bias.
  void operator()(int x, int y, float z) const {
    z = std::clamp(less ? z - depthBias : z + depthBias, 0.0f, 1.0f);
    const size_t p = target.index(x, y);
    if (state.depthTest) {
      if (less ? !(z < target.depth[p]) : !(z > target.depth[p])) return;
      if (state.depthWrite) target.depth[p] = z;
    }
    if (writeColor) target.color[p] = color;
    if (countHits) ++target.hits[p];
  }
};

/// The DDA of window-space segment q0 -> q1 along its major axis (x if xMajor, else y): the
/// pixels whose centre lies in [min, max) of the end points on that axis, and on the minor
/// axis the pixel containing the segment's point there.
void rasterLine(const glm::dvec3& q0, const glm::dvec3& q1, bool xMajor, const LineFragments& frag) {
  const int major = xMajor ? 0 : 1, minor = 1 - major;
  const double lo = std::min(q0[major], q1[major]), hi = std::max(q0[major], q1[major]);
  const double span = q1[major] - q0[major];
  if (span == 0) return;
  const int first = int(std::ceil(lo - 0.5)), last = int(std::ceil(hi - 0.5)) - 1;
  for (int k = first; k <= last; ++k) {
    const double t = (k + 0.5 - q0[major]) / span;
    const int m = int(std::floor(q0[minor] + t * (q1[minor] - q0[minor])));
    const int x = xMajor ? k : m, y = xMajor ? m : k;
    if (frag.inside(x, y)) frag(x, y, float(q0.z + t * (q1.z - q0.z)));
  }
}

/// Draws clip-space segment (a, b): clipping, projection, viewport clipping, DDA.
void drawSegment(glm::dvec4 a, glm::dvec4 b, bool zeroToOne, const LineFragments& frag) {
  if (!clipNearFar(a, b, zeroToOne)) return;
  const int W = frag.target.width, H = frag.target.height;
  const glm::dvec3 p0 = toWindow(a, W, H, zeroToOne), p1 = toWindow(b, W, H, zeroToOne);
  const glm::dvec3 d = p1 - p0;
  double t0, t1;
  if (!clipToViewport(p0, d, W, H, t0, t1)) return;
  rasterLine(p0 + d * t0, p0 + d * t1, std::abs(d.x) >= std::abs(d.y), frag);
}

/// The vertex indices of segment s (from `indices`, or 2s and 2s + 1 without them), checked
/// against vertexCount.
std::pair<size_t, size_t> segmentEnds(const uint32_t* indices, size_t s, size_t vertexCount) {
  size_t i0 = 2 * s, i1 = 2 * s + 1;
  if (indices) {
    i0 = indices[2 * s];
    i1 = indices[2 * s + 1];
  }
  if (i0 >= vertexCount || i1 >= vertexCount)
    throw std::out_of_range("raster::drawLines: vertex index out of range");
  return {i0, i1};
}

}  // namespace

void drawLines(Target& target, const State& state, const glm::vec4* clip, size_t vertexCount,
               const uint32_t* indices, size_t lineCount, const glm::vec4& color, float depthBias) {
  if (target.width <= 0 || target.height <= 0) return;
  const PixelRange range = detail::drawableRange(target, state);
  if (range.empty()) return;
  const LineFragments frag{target, state, range, color, depthBias,
                           state.depthFunc == DepthFunc::Less, !target.color.empty(),
                           target.hits.size() == size_t(target.width) * target.height};
  const bool zeroToOne = state.clipDepth == ClipDepth::ZeroToOne;
  for (size_t s = 0; s < lineCount; ++s) {
    const auto [i0, i1] = segmentEnds(indices, s, vertexCount);
    drawSegment(glm::dvec4(clip[i0]), glm::dvec4(clip[i1]), zeroToOne, frag);
  }
}

}  // namespace raster
