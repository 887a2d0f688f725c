// Interpolation across a window-space triangle: attribute planes, the depth plane (linear in
// window space) and perspective-correct Gouraud colour.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "display/raster/raster_internal.h"

namespace raster::detail {

// Gradient of an attribute with values a0,a1,a2 at the vertices of a window-space triangle.
struct Plane {
  double x10, y10, x20, y20, inv;
  void gradient(double a0, double a1, double a2, double& gx, double& gy) const {
    const double a10 = a1 - a0, a20 = a2 - a0;
    gx = (rounded(a10 * y20) - rounded(a20 * y10)) * inv;
    gy = (rounded(a20 * x10) - rounded(a10 * x20)) * inv;
  }
};

/// Attribute planes of counter-clockwise triangle (v0, v1, v2), twice its snapped area `area`:
/// from the exact (unsnapped) positions, or the snapped ones if those degenerate.
inline Plane makePlane(const SVert& v0, const SVert& v1, const SVert& v2, int64_t area) {
  Plane pl{double(v1.x) - v0.x, double(v1.y) - v0.y, double(v2.x) - v0.x, double(v2.y) - v0.y, 0};
  double det = rounded(pl.x10 * pl.y20) - rounded(pl.x20 * pl.y10);
  if (!(det > 0.0)) {
    const double s = 1.0 / kOne;
    pl = Plane{(v1.X - v0.X) * s, (v1.Y - v0.Y) * s, (v2.X - v0.X) * s, (v2.Y - v0.Y) * s, 0};
    det = double(area) * s * s;
  }
  pl.inv = 1.0 / det;
  return pl;
}

// Depth of a triangle at the centre of its first pixel (ix0, iy0), and its gradient.
struct DepthPlane {
  double z00, dzdx, dzdy;
};

/// The depth plane of triangle (v0, v1, v2) with attribute planes `pl`, from pixel (ix0, iy0).
inline DepthPlane depthAt(const Plane& pl, const SVert& v0, const SVert& v1, const SVert& v2,
                          int ix0, int iy0) {
  const double cx = ix0 + 0.5 - v0.x, cy = iy0 + 0.5 - v0.y;  // centre of (ix0, iy0) rel. v0
  DepthPlane d;
  pl.gradient(v0.z, v1.z, v2.z, d.dzdx, d.dzdy);
  d.z00 = v0.z + rounded(d.dzdx * cx) + rounded(d.dzdy * cy);
  return d;
}

/// Depth at the first pixel of row offset dj (float; the pixels step from it in float).
inline float depthRowStart(const DepthPlane& d, double dj) {
  return float(d.z00 + rounded(d.dzdy * dj));
}

/// Depth clamp to [0, 1], written to match SSE maxps/minps bit for bit.
inline float clampDepth(float z) {
  z = z > 0.0f ? z : 0.0f;
  return z < 1.0f ? z : 1.0f;
}

// Smooth shading: q = 1/w and s_k = lambda_k/w are affine in window space, so the barycentric
// weights lambda_1 = s_1/q and lambda_2 = s_2/q are perspective-correct.
struct Gouraud {
  double qx = 0, qy = 0, ax = 0, ay = 0, bx = 0, by = 0, q00 = 0, a00 = 0, b00 = 0;
  glm::vec4 c0{0.0f}, c10{0.0f}, c20{0.0f};

  /// The planes of triangle (v0, v1, v2) (attribute planes `pl`) from pixel (ix0, iy0).
  Gouraud(const Plane& pl, const SVert& v0, const SVert& v1, const SVert& v2, int ix0, int iy0) {
    const double cx = ix0 + 0.5 - v0.x, cy = iy0 + 0.5 - v0.y;  // centre of (ix0, iy0) rel. v0
    pl.gradient(v0.q, v1.q, v2.q, qx, qy);
    pl.gradient(0.0, v1.q, 0.0, ax, ay);
    pl.gradient(0.0, 0.0, v2.q, bx, by);
    q00 = v0.q + qx * cx + qy * cy;
    a00 = ax * cx + ay * cy;
    b00 = bx * cx + by * cy;
    c0 = *v0.color;
    c10 = *v1.color - c0;
    c20 = *v2.color - c0;
  }
  Gouraud() = default;

  /// Colour at pixel offset (fk, dj) from (ix0, iy0).
  glm::vec4 at(float fk, double dj) const {
    const double q = q00 + qx * fk + qy * dj;
    const double la = (a00 + ax * fk + ay * dj) / q, lb = (b00 + bx * fk + by * dj) / q;
    return c0 + float(la) * c10 + float(lb) * c20;
  }
};

}  // namespace raster::detail
