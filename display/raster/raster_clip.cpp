// Homogeneous clipping. Clipping works in double precision: a near-plane cut subtracts nearly
// equal w values, and in float the cut points of one triangle can come out in the wrong order
// far out in the guard band, which turned convex polygons concave and lost whole fan triangles
// (regression test NearPlaneCutNearTheEyeStaysConvex).
#include "display/raster/raster_clip.h"

#include <cfloat>
#include <cmath>
#include <utility>

#include "display/raster/raster_triangle.h"

namespace raster::detail {
namespace {

constexpr uint32_t kGenerated = 0xFFFFFFFFu;  // CVert::src of a vertex made by clipping
constexpr int kMaxPoly = 16;                  // convex triangle clipped by 6 planes: <= 9

// A polygon vertex during clipping.
struct CVert {
  glm::dvec4 pos;
  glm::vec4 col;
  uint32_t src;  // original vertex index, or kGenerated
};

/// Signed distance of v to clipping plane p (0 near, 1 far, 2-5 guard left/right/bottom/top),
/// inside iff >= 0: the vertex stage's planeDist in double.
inline double planeDistD(const glm::dvec4& v, int p, const Frame& f) {
  switch (p) {
    case 0: return v.z + double(f.nearW) * v.w;
    case 1: return v.w - v.z;
    case 2: return v.x + double(f.gx) * v.w;
    case 3: return double(f.gx) * v.w - v.x;
    case 4: return v.y + double(f.gy) * v.w;
    default: return double(f.gy) * v.w - v.y;
  }
}

/// Clip space (double) -> (x_w, y_w, depth, 1/w), for vertices made by clipping.
inline glm::vec4 projectD(const glm::dvec4& v, const Frame& f) {
  const double q = 1.0 / v.w;
  return glm::vec4(float((v.x * q + 1.0) * f.halfW), float((v.y * q + 1.0) * f.halfH),
                   float(v.z * q * f.zScale + f.zBias), float(q));
}

/// Puts a vertex made on plane p exactly on it.
inline void putOnPlane(glm::dvec4& pos, int p, const Frame& f) {
  switch (p) {
    case 0: pos.z = -(double(f.nearW) * pos.w); break;
    case 1: pos.z = pos.w; break;
    case 2: pos.x = -(double(f.gx) * pos.w); break;
    case 3: pos.x = double(f.gx) * pos.w; break;
    case 4: pos.y = -(double(f.gy) * pos.w); break;
    default: pos.y = double(f.gy) * pos.w; break;
  }
}

/// Intersection of edge (in, out) with plane p. Always computed from the inside vertex, so an
/// edge shared by two triangles is cut at bit-identical points whatever its direction.
inline CVert intersect(const CVert& in, double din, const CVert& out, double dout, int p,
                       const Frame& f) {
  const double t = din / (din - dout);
  CVert r;
  r.pos = in.pos + t * (out.pos - in.pos);
  r.col = in.col + float(t) * (out.col - in.col);
  r.src = kGenerated;
  putOnPlane(r.pos, p, f);
  return r;
}

/// Distances d of polygon poly[0..n) to plane p; whether some vertex is outside.
bool planeDistances(const CVert* poly, int n, int p, const Frame& f, double (&d)[kMaxPoly]) {
  bool anyOut = false;
  for (int k = 0; k < n; ++k) {
    d[k] = planeDistD(poly[k].pos, p, f);
    anyOut |= !(d[k] >= 0.0);
  }
  return anyOut;
}

/// Cuts polygon poly[0..n) with distances d to plane p, keeping the inside, into `next`;
/// returns its vertex count, or -1 if it would overflow (impossible for finite input).
int cutPolygon(const CVert* poly, int n, const double (&d)[kMaxPoly], int p, const Frame& f,
               CVert* next) {
  int m = 0;
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    const bool in0 = d[k] >= 0.0, in1 = d[k1] >= 0.0;
    if (m + 2 > kMaxPoly) return -1;
    if (in0) next[m++] = poly[k];
    if (in0 != in1)
      next[m++] = in0 ? intersect(poly[k], d[k], poly[k1], d[k1], p, f)
                      : intersect(poly[k1], d[k1], poly[k], d[k], p, f);
  }
  return m;
}

/// Triangle vi as the clipper's first polygon, in `poly` (colours only for smooth shading).
template <Shade S>
inline void loadTriangle(const Vertices& v, const uint32_t (&vi)[3], CVert* poly) {
  for (int k = 0; k < 3; ++k) {
    poly[k].pos = glm::dvec4(v.clip[vi[k]]);
    poly[k].col = (S == Shade::Smooth) ? v.colors[vi[k]] : glm::vec4(0.0f);
    poly[k].src = vi[k];
  }
}

/// Clips triangle vi against every plane, using bufA and bufB; returns the polygon (in one of
/// them) and sets n to its vertex count, < 3 if nothing is left. Every plane is tested (not only
/// those flagged by the triangle's outcodes) so that adjacent triangles cut their shared edge
/// identically even after rounding in earlier planes.
template <Shade S>
const CVert* clipTriangle(const Vertices& v, const uint32_t (&vi)[3], const Frame& f, CVert* bufA,
                          CVert* bufB, int& n) {
  CVert* poly = bufA;
  CVert* next = bufB;
  n = 3;
  loadTriangle<S>(v, vi, poly);
  for (int p = 0; p < kPlaneCount; ++p) {
    double d[kMaxPoly];
    if (!planeDistances(poly, n, p, f, d)) continue;
    n = cutPolygon(poly, n, d, p, f, next);
    std::swap(poly, next);
    if (n < 3) break;
  }
  return poly;
}

/// Whether a vertex made by clipping projects within the guard band and the depth range, with a
/// finite positive 1/w.
inline bool projectable(const glm::vec4& w) {
  const float lim = kGuardPixels + 1.0f;
  return std::fabs(w.x) <= lim && std::fabs(w.y) <= lim && std::fabs(w.z) <= 2.0f && w.w > 0.0f &&
         w.w <= FLT_MAX;
}

/// Snaps the clipped polygon poly[0..n) into sv; false if a vertex cannot be projected (NaN
/// input, or the zero vector as a vertex). Original vertices that survived use the vertex
/// stage's values, exactly as the unclipped triangles sharing them do (the outcodes and the
/// clipper agree on inside/outside).
bool snapPolygon(const CVert* poly, int n, const Vertices& v, const Frame& f, SVert* sv) {
  for (int k = 0; k < n; ++k) {
    const uint32_t s = poly[k].src;
    if (s != kGenerated && !(v.codes[s] & kClipBits)) {
      sv[k] = makeSVert(v.win[s], v.fixed[s], &poly[k].col);
      continue;
    }
    const glm::vec4 w = projectD(poly[k].pos, f);
    if (!projectable(w)) return false;
    sv[k] = makeSVert(w, &poly[k].col);
  }
  return true;
}

/// Draws the fan of snapped polygon sv[0..n) from vertex 0; the polygon's orientation decides
/// culling, and fan slivers whose orientation flipped through snapping are dropped.
template <bool Fast, Shade S, bool Greater>
void drawFan(const Ctx& c, const SVert* sv, int n) {
  int64_t fan[kMaxPoly];
  int64_t total = 0;
  for (int k = 1; k + 1 < n; ++k) total += fan[k] = area2(sv[0], sv[k], sv[k + 1]);
  if (total == 0 || (total < 0 && c.cullBack)) return;
  for (int k = 1; k + 1 < n; ++k) {
    if (total > 0 && fan[k] > 0)
      rasterTriangle<Fast, S, Greater>(c, sv[0], sv[k], sv[k + 1], fan[k]);
    else if (total < 0 && fan[k] < 0)
      rasterTriangle<Fast, S, Greater>(c, sv[0], sv[k + 1], sv[k], -fan[k]);
  }
}

}  // namespace

template <bool Fast, Shade S, bool Greater>
void clipAndDraw(const Ctx& c, const Frame& f, const Vertices& v, const uint32_t (&vi)[3]) {
  CVert bufA[kMaxPoly], bufB[kMaxPoly];
  int n;
  const CVert* poly = clipTriangle<S>(v, vi, f, bufA, bufB, n);
  SVert sv[kMaxPoly];
  if (n < 3 || !snapPolygon(poly, n, v, f, sv)) return;
  drawFan<Fast, S, Greater>(c, sv, n);
}

#define RASTER_INSTANTIATE(Fast, S, Greater) \
  template void clipAndDraw<Fast, S, Greater>(const Ctx&, const Frame&, const Vertices&, \
                                              const uint32_t (&)[3]);
RASTER_FOR_EACH_PIPELINE(RASTER_INSTANTIATE)
#undef RASTER_INSTANTIATE

}  // namespace raster::detail
