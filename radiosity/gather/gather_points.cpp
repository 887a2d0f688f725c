#include "radiosity/gather/gather_points.h"

#include <algorithm>
#include <array>

#include <glm/geometric.hpp>

#include "mesh/refine.h"
#include "radiosity/light/direct_light.h"

namespace rad {
namespace {

using Field = std::vector<glm::dvec3>;
/// For each vertex of the base mesh, the refined mesh's vertex at the same place (-1: none).
using BaseCorners = std::vector<int>;

/// Vertex v's place.
glm::dvec3 position(const PatchMesh& m, TriMesh::VertexHandle v) { return PatchMesh::toGlm(m.mesh.point(v)); }

/// The corners of base element j, as base vertex handles.
std::array<TriMesh::VertexHandle, 3> corners(const PatchMesh& base, int j) {
  std::array<TriMesh::VertexHandle, 3> out;
  int k = 0;
  for (auto v : base.mesh.fv_range(TriMesh::FaceHandle(j))) out[size_t(k++)] = v;
  return out;
}

/// Which refined vertex each base vertex became: the corner of a refined element at exactly
/// the place of a corner of its base element.
BaseCorners baseCorners(const PatchMesh& mesh, const PatchMesh& base) {
  BaseCorners out(base.mesh.n_vertices(), -1);
  for (auto f : mesh.mesh.faces()) {
    const auto baseCorner = corners(base, mesh.base(f.idx()));
    for (auto v : mesh.mesh.fv_range(f))
      for (auto b : baseCorner)
        if (position(mesh, v) == position(base, b)) out[size_t(b.idx())] = v.idx();
  }
  return out;
}

/// Barycentric weights of p in triangle t (projected onto its plane), negative ones clamped.
std::array<double, 3> barycentric(const std::array<glm::dvec3, 3>& t, const glm::dvec3& p) {
  const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
  std::array<double, 3> w;
  for (int i = 0; i < 3; ++i)
    w[size_t(i)] = std::max(0.0, glm::dot(n, glm::cross(t[size_t((i + 1) % 3)] - p, t[size_t((i + 2) % 3)] - p)));
  const double sum = w[0] + w[1] + w[2];
  if (sum <= 0) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  for (double& x : w) x /= sum;
  return w;
}

/// Vertex v of refined element e, inside base element j: the weights of the refined vertices at
/// j's corners, or none when one of them is missing.
std::vector<std::pair<int, double>> interpolated(const PatchMesh& mesh, const PatchMesh& base,
                                                 const BaseCorners& at, int e, TriMesh::VertexHandle v) {
  const auto baseCorner = corners(base, mesh.base(e));
  std::array<glm::dvec3, 3> t;
  for (size_t k = 0; k < 3; ++k) {
    if (at[size_t(baseCorner[k].idx())] < 0) return {};
    t[k] = position(base, baseCorner[k]);
  }
  const auto w = barycentric(t, position(mesh, v));
  std::vector<std::pair<int, double>> out;
  for (size_t k = 0; k < 3; ++k)
    if (w[k] > 0) out.emplace_back(at[size_t(baseCorner[k].idx())], w[k]);
  return out;
}

/// Makes vertex v gather for itself, through the hemicube of the drawn mesh's vertex `drawn`
/// (-1: its own).
void gatherAt(GatherPoints& g, int v, int drawn) {
  g.at[size_t(v)] = true;
  g.from[size_t(v)] = {{v, 1.0}};
  g.drawn[size_t(v)] = drawn;
}

}  // namespace

Field GatherPoints::spread(const Field& atPoints) const {
  Field out(from.size(), glm::dvec3(0.0));
  for (size_t v = 0; v < from.size(); ++v)
    for (const auto& [p, w] : from[v]) out[v] += w * atPoints[size_t(p)];
  return out;
}

int GatherPoints::count() const { return int(std::count(at.begin(), at.end(), true)); }

std::vector<char> nearSurfaces(const PatchMesh& mesh, const PatchMesh& base, const DirectLight& light) {
  std::vector<double> reach(mesh.mesh.n_vertices(), 0.0);
  for (auto f : mesh.mesh.faces()) {
    if (mesh.reflectance(f.idx()) == glm::dvec3(0.0)) continue;  // black: gathers nothing
    const double edge = longestEdge(base, mesh.base(f.idx()));
    for (auto v : mesh.mesh.fv_range(f)) reach[size_t(v.idx())] = std::max(reach[size_t(v.idx())], edge);
  }
  for (int v : baseCorners(mesh, base))
    if (v >= 0) reach[size_t(v)] = 0;
  const std::vector<int> met = light.surfacesWithin(mesh, reach);
  std::vector<char> out(met.size(), 0);
  for (size_t v = 0; v < met.size(); ++v) out[v] = met[v] > 0;
  return out;
}

GatherPoints gatherPoints(const PatchMesh& mesh, const PatchMesh* base, const Field& rho,
                          const std::vector<char>* ownHemicube, const DrawnInterpolation* drawn) {
  const size_t n = mesh.mesh.n_vertices();
  GatherPoints g{std::vector<bool>(n, false), std::vector<std::vector<std::pair<int, double>>>(n),
                 std::vector<int>(n, -1)};
  // Whether drawn vertex d gathers itself (else it interpolates drawn's others).
  auto drawnGathers = [&](size_t d) {
    return !drawn || drawn->empty() || ((*drawn)[d].size() == 1 && (*drawn)[d][0].first == int(d));
  };
  if (!base) {
    for (size_t v = 0; v < n; ++v)
      if (rho[v] != glm::dvec3(0.0)) {
        if (drawnGathers(v))
          gatherAt(g, int(v), int(v));
        else
          g.from[v] = (*drawn)[v];
      }
    return g;
  }
  const BaseCorners at = baseCorners(mesh, *base);
  for (size_t b = 0; b < at.size(); ++b)
    if (at[b] >= 0 && rho[size_t(at[b])] != glm::dvec3(0.0) && drawnGathers(b)) gatherAt(g, at[b], int(b));
  for (size_t b = 0; b < at.size(); ++b) {
    if (at[b] < 0 || rho[size_t(at[b])] == glm::dvec3(0.0) || drawnGathers(b)) continue;
    auto& from = g.from[size_t(at[b])];
    for (const auto& [d, w] : (*drawn)[b])
      if (at[size_t(d)] >= 0 && g.at[size_t(at[size_t(d)])]) from.emplace_back(at[size_t(d)], w);
    if (from.size() != (*drawn)[b].size()) gatherAt(g, at[b], -1);  // one it takes is lost: its own
  }
  // A vertex inside a base element: its corners' light, each as that corner has it.
  auto expand = [&](const std::vector<std::pair<int, double>>& corners) {
    std::vector<std::pair<int, double>> out;
    for (const auto& [c, w] : corners) {
      if (g.at[size_t(c)]) {
        out.emplace_back(c, w);
        continue;
      }
      for (const auto& [p, wp] : g.from[size_t(c)]) out.emplace_back(p, w * wp);
    }
    return out;
  };
  for (auto f : mesh.mesh.faces())
    for (auto v : mesh.mesh.fv_range(f)) {
      if (!g.from[size_t(v.idx())].empty() || rho[size_t(v.idx())] == glm::dvec3(0.0)) continue;
      if (ownHemicube && !ownHemicube->empty() && (*ownHemicube)[size_t(v.idx())]) {
        gatherAt(g, v.idx(), -1);
        continue;
      }
      g.from[size_t(v.idx())] = expand(interpolated(mesh, *base, at, f.idx(), v));
      if (g.from[size_t(v.idx())].empty()) gatherAt(g, v.idx(), -1);  // its base element's corner is lost
    }
  return g;
}

}  // namespace rad
