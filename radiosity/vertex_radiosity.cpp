#include "radiosity/vertex_radiosity.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "mesh/base/error.h"

namespace rad {

namespace {

/// Elements whose normals agree this well lie in one plane.
constexpr double kSamePlane = 1 - 1e-9;
/// Below this (relative) determinant the elements' centroids around a vertex are too nearly
/// collinear for a linear fit.
constexpr double kFitConditioning = 1e-6;

/// The elements round v and their neighbours, in the plane of v's first element (a mesh
/// file's surface may fold: its other planes do not take part), sorted, each once; and that
/// plane's normal.
std::vector<int> planarFacesAround(const PatchMesh& m, TriMesh::VertexHandle v, glm::dvec3& n) {
  std::vector<int> faces;
  n = glm::dvec3(0.0);
  for (auto f : m.mesh.vf_range(v)) {
    if (n == glm::dvec3(0.0)) n = m.normal(f.idx());
    for (auto w : m.mesh.fv_range(f))
      for (auto g : m.mesh.vf_range(w))
        if (glm::dot(m.normal(g.idx()), n) > kSamePlane) faces.push_back(g.idx());
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

/// Normal equations of B ≈ a + b·x + c·y over element centroids, x and y along u and w from
/// p in units of `scale`, weighted by area; with the range of the values.
struct LinearFit {
  glm::dmat3 A{0.0};
  glm::dvec3 rhs[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};  // per channel
  glm::dvec3 lo{HUGE_VAL}, hi{-HUGE_VAL};
  double weights = 0;

  void add(const glm::dvec3& basis, double weight, const glm::dvec3& value) {
    weights += weight;
    A += weight * glm::outerProduct(basis, basis);
    for (int c = 0; c < 3; ++c) rhs[c] += weight * value[c] * basis;
    lo = glm::min(lo, value);
    hi = glm::max(hi, value);
  }

  /// The fit's value at the origin, kept within the span of the values stretched by the span
  /// on either side, and non-negative; false when the centroids are too nearly collinear.
  bool atOrigin(glm::dvec3& out) const {
    if (!(std::abs(glm::determinant(A / weights)) > kFitConditioning)) return false;
    const glm::dmat3 inverse = glm::inverse(A);
    const glm::dvec3 span = hi - lo;
    for (int c = 0; c < 3; ++c) {
      const double floor = std::max(0.0, lo[c] - span[c]), ceiling = std::max(floor, hi[c] + span[c]);
      out[c] = std::clamp((inverse * rhs[c]).x, floor, ceiling);
    }
    return true;
  }
};

/// Mean distance from p to the faces' centroids.
double meanDistance(const PatchMesh& m, const std::vector<int>& faces, const glm::dvec3& p) {
  double scale = 0;
  for (int f : faces) scale += glm::length(m.centroid(f) - p);
  return scale / double(faces.size());
}

/// The value at boundary vertex v of the linear function fitted, by area-weighted least
/// squares in the surface's plane, to the element values at their centroids over the elements
/// around v and their neighbours (LinearFit::atOrigin). False when it cannot be fitted.
bool fitAtBoundary(const PatchMesh& m, const std::vector<glm::dvec3>& B, TriMesh::VertexHandle v,
                   glm::dvec3& out) {
  glm::dvec3 n;
  const std::vector<int> faces = planarFacesAround(m, v, n);
  if (faces.size() < 3) return false;
  const glm::dvec3 p = PatchMesh::toGlm(m.mesh.point(v));
  const glm::dvec3 u = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 w = glm::cross(n, u);
  const double scale = meanDistance(m, faces, p);
  LinearFit fit;
  for (int f : faces) {
    const glm::dvec3 d = (m.centroid(f) - p) / scale;
    fit.add(glm::dvec3(1.0, glm::dot(d, u), glm::dot(d, w)), m.area(f), B[size_t(f)]);
  }
  return fit.atOrigin(out);
}

/// Area-weighted means of the element values over each base element.
std::vector<glm::dvec3> baseMeans(const PatchMesh& m, const PatchMesh& base, const std::vector<glm::dvec3>& value) {
  const int n = base.elementCount();
  std::vector<glm::dvec3> mean(size_t(n), glm::dvec3(0.0));
  std::vector<double> area(size_t(n), 0.0);
  for (int e = 0; e < m.elementCount(); ++e) {
    const int b = m.base(e);
    RAD_CHECK(b >= 0 && b < n);
    mean[size_t(b)] += m.area(e) * value[size_t(e)];
    area[size_t(b)] += m.area(e);
  }
  for (int b = 0; b < n; ++b)
    if (area[size_t(b)] > 0) mean[size_t(b)] /= area[size_t(b)];
  return mean;
}

/// The base mesh's vertex values interpolated linearly (barycentric coordinates) at point p
/// in the plane of base element b.
glm::dvec3 interpolateInBase(const PatchMesh& base, int b, const std::vector<glm::dvec3>& atBase, const glm::dvec3& p) {
  const auto c = base.corners(b);
  const glm::dvec3 normal = glm::cross(c[1] - c[0], c[2] - c[0]);
  const double twice = glm::dot(normal, normal);
  glm::dvec3 sum(0.0);
  int k = 0;
  for (auto w : base.mesh.fv_range(TriMesh::FaceHandle(b))) {
    const glm::dvec3 &a = c[size_t((k + 1) % 3)], &d = c[size_t((k + 2) % 3)];
    const double weight = std::max(0.0, glm::dot(glm::cross(d - a, p - a), normal) / twice);
    sum += weight * atBase[size_t(w.idx())];
    ++k;
  }
  return sum;
}

/// The base element a refined mesh's vertex lies in (-1 for an isolated vertex).
int baseElementOf(const PatchMesh& m, TriMesh::VertexHandle v) {
  for (auto f : m.mesh.vf_range(v)) return m.base(f.idx());
  return -1;
}

/// Element values averaged over their base elements, reconstructed at the base mesh's
/// vertices, and interpolated at the refined mesh's vertices inside their base elements.
std::vector<glm::dvec3> substructured(const PatchMesh& m, const PatchMesh& base,
                                      const std::vector<glm::dvec3>& value) {
  const std::vector<glm::dvec3> atBase = vertexRadiosity(base, baseMeans(m, base, value));
  std::vector<glm::dvec3> out(m.mesh.n_vertices(), glm::dvec3(0.0));
  for (auto v : m.mesh.vertices()) {
    if (size_t(v.idx()) < atBase.size()) {  // a vertex of the base mesh (vertices are only added)
      out[size_t(v.idx())] = atBase[size_t(v.idx())];
      continue;
    }
    const int b = baseElementOf(m, v);
    if (b >= 0) out[size_t(v.idx())] = interpolateInBase(base, b, atBase, PatchMesh::toGlm(m.mesh.point(v)));
  }
  return out;
}

/// The area-weighted mean of the elements around vertex v (0 for an isolated vertex).
glm::dvec3 areaMeanAround(const PatchMesh& m, const std::vector<glm::dvec3>& B, TriMesh::VertexHandle v) {
  double area = 0;
  glm::dvec3 sum(0.0);
  for (auto f : m.mesh.vf_range(v)) {
    sum += m.area(f.idx()) * B[f.idx()];
    area += m.area(f.idx());
  }
  return area > 0 ? sum / area : glm::dvec3(0.0);
}

/// Barycentric coordinates w of x in element e, if x lies in it (within its plane's
/// tolerance of 1e-6 of its size, and 1e-12 outside its edges).
bool barycentricIn(const PatchMesh& m, int e, const glm::dvec3& x, double w[3]) {
  const auto c = m.corners(e);
  const glm::dvec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
  const double twice = glm::dot(n, n), size = std::sqrt(std::sqrt(twice));  // |n| = 2·area
  if (!(twice > 0) || std::abs(glm::dot(x - c[0], n)) / std::sqrt(twice) > 1e-6 * size) return false;
  for (size_t k = 0; k < 3; ++k) {
    w[k] = glm::dot(glm::cross(c[(k + 2) % 3] - c[(k + 1) % 3], x - c[(k + 1) % 3]), n) / twice;
    if (w[k] < -1e-12) return false;
  }
  return true;
}

}  // namespace

std::vector<glm::dvec3> vertexRadiosity(const PatchMesh& m, const std::vector<glm::dvec3>& B) {
  std::vector<glm::dvec3> out(m.mesh.n_vertices(), glm::dvec3(0.0));
  for (auto v : m.mesh.vertices()) {
    // On a surface's boundary the elements lie on one side only, so their mean is the value
    // some way inwards: fit and extrapolate there instead (the base of a block, where the
    // light changes fastest). Elsewhere, the area-weighted mean.
    if (m.mesh.is_boundary(v) && fitAtBoundary(m, B, v, out[v.idx()])) continue;
    out[v.idx()] = areaMeanAround(m, B, v);
  }
  return out;
}

std::vector<glm::dvec3> vertexRadiosity(const PatchMesh& m, const std::vector<glm::dvec3>& B,
                                        const VertexDirect* direct) {
  if (!direct) return vertexRadiosity(m, B);
  RAD_CHECK(direct->element.size() == B.size() && direct->vertex.size() == m.mesh.n_vertices());
  std::vector<glm::dvec3> rest(B);
  for (size_t e = 0; e < B.size(); ++e) rest[e] -= direct->element[e];
  std::vector<glm::dvec3> out = direct->base ? substructured(m, *direct->base, rest) : vertexRadiosity(m, rest);
  for (size_t v = 0; v < out.size(); ++v) out[v] = glm::max(out[v] + direct->vertex[v], glm::dvec3(0.0));
  return out;
}

std::vector<glm::dvec3> shownVertexRadiosity(const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                                             const glm::dvec3& ambient, const VertexDirect* direct) {
  if (ambient == glm::dvec3(0.0)) return vertexRadiosity(mesh, B, direct);
  std::vector<glm::dvec3> shown(B);
  for (int e = 0; e < mesh.elementCount(); ++e) shown[size_t(e)] += mesh.reflectance(e) * ambient;
  return vertexRadiosity(mesh, shown, direct);
}

std::optional<glm::dvec3> gouraudAt(const PatchMesh& m, const std::vector<int>& elements,
                                    const std::vector<glm::dvec3>& vertexValue, const glm::dvec3& x) {
  for (int e : elements) {
    double w[3];
    if (!barycentricIn(m, e, x, w)) continue;
    glm::dvec3 value(0.0);
    int k = 0;
    for (auto v : m.mesh.fv_range(TriMesh::FaceHandle(e))) value += w[k++] * vertexValue[size_t(v.idx())];
    return value;
  }
  return std::nullopt;
}

}  // namespace rad
