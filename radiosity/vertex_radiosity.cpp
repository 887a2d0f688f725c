#include "radiosity/vertex_radiosity.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "mesh/error.h"

namespace rad {

namespace {

/// Elements whose normals agree this well lie in one plane.
constexpr double kSamePlane = 1 - 1e-9;
/// Below this (relative) determinant the elements' centroids around a vertex are too nearly
/// collinear for a linear fit.
constexpr double kFitConditioning = 1e-6;

/// The value at boundary vertex v of the linear function fitted, by area-weighted least
/// squares in the surface's plane, to the element values at their centroids over the elements
/// around v and their neighbours; kept within the span of those values stretched by the span
/// on either side, and non-negative. False when the centroids are too nearly collinear.
bool fitAtBoundary(const PatchMesh& m, const std::vector<glm::dvec3>& B, TriMesh::VertexHandle v,
                   glm::dvec3& out) {
  // The elements round v and their neighbours, in the plane of v's first element (a mesh
  // file's surface may fold: its other planes do not take part).
  std::vector<int> faces;
  glm::dvec3 n(0.0);
  for (auto f : m.mesh.vf_range(v)) {
    if (n == glm::dvec3(0.0)) n = m.normal(f.idx());
    for (auto w : m.mesh.fv_range(f))
      for (auto g : m.mesh.vf_range(w))
        if (glm::dot(m.normal(g.idx()), n) > kSamePlane) faces.push_back(g.idx());
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  if (faces.size() < 3) return false;
  const glm::dvec3 p = PatchMesh::toGlm(m.mesh.point(v));
  const glm::dvec3 u = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 w = glm::cross(n, u);
  double scale = 0;
  for (int f : faces) scale += glm::length(m.centroid(f) - p);
  scale /= double(faces.size());
  // Normal equations of B ≈ a + b·x + c·y, x and y in units of `scale`.
  glm::dmat3 A(0.0);
  glm::dvec3 rhs[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};  // per channel
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  double weights = 0;
  for (int f : faces) {
    const glm::dvec3 d = (m.centroid(f) - p) / scale;
    const glm::dvec3 basis(1.0, glm::dot(d, u), glm::dot(d, w));
    const double weight = m.area(f);
    weights += weight;
    A += weight * glm::outerProduct(basis, basis);
    for (int c = 0; c < 3; ++c) rhs[c] += weight * B[size_t(f)][c] * basis;
    lo = glm::min(lo, B[size_t(f)]);
    hi = glm::max(hi, B[size_t(f)]);
  }
  if (!(std::abs(glm::determinant(A / weights)) > kFitConditioning)) return false;
  const glm::dmat3 inverse = glm::inverse(A);
  const glm::dvec3 span = hi - lo;
  for (int c = 0; c < 3; ++c) {
    const double floor = std::max(0.0, lo[c] - span[c]), ceiling = std::max(floor, hi[c] + span[c]);
    out[c] = std::clamp((inverse * rhs[c]).x, floor, ceiling);
  }
  return true;
}

/// Element values averaged over their base elements, reconstructed at the base mesh's
/// vertices, and interpolated at the refined mesh's vertices inside their base elements.
std::vector<glm::dvec3> substructured(const PatchMesh& m, const PatchMesh& base,
                                      const std::vector<glm::dvec3>& value) {
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
  const std::vector<glm::dvec3> atBase = vertexRadiosity(base, mean);
  std::vector<glm::dvec3> out(m.mesh.n_vertices(), glm::dvec3(0.0));
  for (auto v : m.mesh.vertices()) {
    if (size_t(v.idx()) < atBase.size()) {  // a vertex of the base mesh (vertices are only added)
      out[size_t(v.idx())] = atBase[size_t(v.idx())];
      continue;
    }
    int b = -1;
    for (auto f : m.mesh.vf_range(v)) {
      b = m.base(f.idx());
      break;
    }
    if (b < 0) continue;
    // Barycentric coordinates in the base element (the vertex lies in its plane).
    const auto c = base.corners(b);
    const glm::dvec3 p = PatchMesh::toGlm(m.mesh.point(v));
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
    out[size_t(v.idx())] = sum;
  }
  return out;
}

}  // namespace

std::vector<glm::dvec3> vertexRadiosity(const PatchMesh& m, const std::vector<glm::dvec3>& B) {
  std::vector<glm::dvec3> out(m.mesh.n_vertices(), glm::dvec3(0.0));
  for (auto v : m.mesh.vertices()) {
    // On a surface's boundary the elements lie on one side only, so their mean is the value
    // some way inwards: fit and extrapolate there instead (the base of a block, where the
    // light changes fastest). Elsewhere, the area-weighted mean.
    if (m.mesh.is_boundary(v) && fitAtBoundary(m, B, v, out[v.idx()])) continue;
    double area = 0;
    glm::dvec3 sum(0.0);
    for (auto f : m.mesh.vf_range(v)) {
      sum += m.area(f.idx()) * B[f.idx()];
      area += m.area(f.idx());
    }
    out[v.idx()] = area > 0 ? sum / area : glm::dvec3(0.0);
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
    const auto c = m.corners(e);
    const glm::dvec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
    const double twice = glm::dot(n, n), size = std::sqrt(std::sqrt(twice));  // |n| = 2·area
    if (!(twice > 0) || std::abs(glm::dot(x - c[0], n)) / std::sqrt(twice) > 1e-6 * size) continue;
    double w[3];
    bool inside = true;
    for (size_t k = 0; k < 3 && inside; ++k) {
      w[k] = glm::dot(glm::cross(c[(k + 2) % 3] - c[(k + 1) % 3], x - c[(k + 1) % 3]), n) / twice;
      inside = w[k] >= -1e-12;
    }
    if (!inside) continue;
    glm::dvec3 value(0.0);
    int k = 0;
    for (auto v : m.mesh.fv_range(TriMesh::FaceHandle(e))) value += w[k++] * vertexValue[size_t(v.idx())];
    return value;
  }
  return std::nullopt;
}

}  // namespace rad
