#include "radiosity/adaptive.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/base/color.h"
#include "mesh/base/error.h"
#include "mesh/base/progress.h"
#include "mesh/refine.h"
#include "mesh/scene/geometry.h"
#include "radiosity/result.h"
#include "radiosity/settings.h"

namespace rad {
namespace {

/// The display value (sRGB-encoded, in [0, 1]) of a luminance at exposure K.
double display(double lum, double exposure) {
  return srgbEncode(std::clamp(lum * exposure, 0.0, 1.0));
}

/// Luminance of the light vertex a receives through samples b does not see.
double lightOnlyFrom(const VertexLight& a, const VertexLight& b, const std::vector<int>& lightOf) {
  double sum = 0;
  for (size_t w = 0; w < a.visible.size(); ++w) {
    uint64_t only = a.visible[w] & ~b.visible[w];
    while (only) {
      const int bit = __builtin_ctzll(only);
      only &= only - 1;
      sum += a.weight[size_t(lightOf[w * 64 + size_t(bit)])];
    }
  }
  return sum;
}

/// The mesh quality figures, for the refined mesh (radiosity info prints them).
void updateMeshStats(PatchMesh& mesh) {
  mesh.stats.minAngleDeg = 180;
  mesh.stats.maxEdge = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) {
    const auto c = mesh.corners(e);
    for (size_t k = 0; k < 3; ++k) {
      const glm::dvec3 &a = c[k], &b = c[(k + 1) % 3], &d = c[(k + 2) % 3];
      mesh.stats.minAngleDeg = std::min(mesh.stats.minAngleDeg, angleDeg(a, b, d));
      mesh.stats.maxEdge = std::max(mesh.stats.maxEdge, glm::length(b - a));
    }
  }
}

}  // namespace

DisplayEstimate estimateDisplay(const PatchMesh& mesh, const DirectLight& light) {
  const auto& vertices = light.vertices();
  std::vector<glm::dvec3> B(size_t(mesh.elementCount()), glm::dvec3(0.0));
  glm::dvec3 reflected(0.0), rhoMean(0.0);
  double area = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) {
    glm::dvec3 d(0.0);
    for (auto v : mesh.mesh.fv_range(TriMesh::FaceHandle(e))) d += vertices[size_t(v.idx())].radiosity;
    B[size_t(e)] = mesh.emission(e) + d / 3.0;
    reflected += mesh.area(e) * d / 3.0;
    rhoMean += mesh.area(e) * mesh.reflectance(e);
    area += mesh.area(e);
  }
  DisplayEstimate out;
  if (!(area > 0)) return out;
  rhoMean /= area;
  out.ambient = reflected / area / (glm::dvec3(1.0) - glm::min(rhoMean, glm::dvec3(0.999)));
  for (int e = 0; e < mesh.elementCount(); ++e) B[size_t(e)] += mesh.reflectance(e) * out.ambient;
  out.exposure = autoExposure(mesh, B);
  return out;
}

namespace {

/// Each light sample's light (LightPolygon index), padded to whole 64-bit words.
std::vector<int> lightOfSamples(const DirectLight& light) {
  std::vector<int> lightOf(size_t(light.samples() + 63) / 64 * 64, 0);
  for (size_t t = 0; t < light.lights().size(); ++t)
    for (int j = 0; j < light.lights()[t].count; ++j) lightOf[size_t(light.lights()[t].first + j)] = int(t);
  return lightOf;
}

/// The floor for sharp changes (RefineTest's): elements down to it may still be bisected.
double sharpFloor(const AdaptiveOptions& options) { return options.minElementEdge / kSharpRefinement; }

/// Elements that may be refined (all, or those `among`): larger than the floor for sharp
/// changes, and not black (black shows no light).
std::vector<int> refinable(const PatchMesh& mesh, const AdaptiveOptions& options, const std::vector<int>* among) {
  std::vector<int> out;
  const double floor = sharpFloor(options);
  auto consider = [&](int e) {
    if (longestEdge(mesh, e) > floor && mesh.reflectance(e) != glm::dvec3(0.0)) out.push_back(e);
  };
  if (among)
    std::for_each(among->begin(), among->end(), consider);
  else
    for (int e = 0; e < mesh.elementCount(); ++e) consider(e);
  return out;
}

/// The probe at the midpoint of element e's edge from a to b.
DirectLight::Probe midpointProbe(const PatchMesh& mesh, int e, TriMesh::VertexHandle a, TriMesh::VertexHandle b,
                                 const std::vector<VertexLight>& vertices) {
  const TriMesh& m = mesh.mesh;
  DirectLight::Probe p;
  p.point = (PatchMesh::toGlm(m.point(a)) + PatchMesh::toGlm(m.point(b))) * 0.5;
  p.normal = PatchMesh::toGlm(m.normal(a) + m.normal(b));
  p.normal = glm::length(p.normal) > 0 ? glm::normalize(p.normal) : mesh.normal(e);
  p.rho = mesh.reflectance(e);
  p.inwards = mesh.centroid(e) - p.point;
  p.size = 0.5 * (m.point(a) - m.point(b)).norm();
  // A sample both ends see, or neither, the midpoint sees as they do (a thin occluder seen
  // from neither end is the exception this accepts): rays go only to the samples whose
  // visibility changes along the edge, and to every kAgreementCheck-th of those both see;
  // none where the ends see the same (DirectLight::samplesVisible).
  p.visible = &vertices[size_t(a.idx())].visible;
  if (vertices[size_t(b.idx())].visible != *p.visible) p.alsoVisible = &vertices[size_t(b.idx())].visible;
  return p;
}

/// Computes the light at the midpoints of the candidates' edges not yet in `midpoints`.
void lightMidpoints(const PatchMesh& mesh, DirectLight& light, const std::vector<int>& candidates,
                    MidpointLight& midpoints) {
  const TriMesh& m = mesh.mesh;
  std::vector<DirectLight::Probe> probes;
  std::vector<uint64_t> probed;
  for (int e : candidates)
    for (auto h : m.fh_range(TriMesh::FaceHandle(e))) {
      auto a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
      const uint64_t key = edgeKey(a.idx(), b.idx());
      if (midpoints.count(key)) continue;
      midpoints[key] = VertexLight{};
      probes.push_back(midpointProbe(mesh, e, a, b, light.vertices()));
      probed.push_back(key);
    }
  std::vector<VertexLight> found = light.lightAt(probes);
  for (size_t k = 0; k < probed.size(); ++k) midpoints[probed[k]] = std::move(found[k]);
}

/// What deciding an element's refinement looks at.
struct RefineTest {
  const PatchMesh& mesh;
  const std::vector<VertexLight>& vertices;
  const MidpointLight& midpoints;
  const std::vector<double>& enclosure;
  std::vector<int> lightOf;
  glm::dvec3 ambient;
  double exposure, contrast, minElementEdge;

  /// The display value of a luminance on element e, the ambient estimate added.
  double shown(int e, double lum) const {
    return display(lum + luminance(mesh.reflectance(e) * ambient), exposure);
  }

  /// What Gouraud shading shows at an edge's midpoint against the light there, differing by
  /// more than `threshold`; the edge's start vertices in `corner`.
  bool midpointsDiffer(int e, std::array<int, 3>& corner, double threshold) const {
    const TriMesh& m = mesh.mesh;
    bool differ = false;
    int k = 0;
    for (auto h : m.fh_range(TriMesh::FaceHandle(e))) {
      const int a = m.from_vertex_handle(h).idx(), b = m.to_vertex_handle(h).idx();
      corner[size_t(k++)] = a;
      const double interpolated =
          0.5 * (luminance(vertices[size_t(a)].radiosity) + luminance(vertices[size_t(b)].radiosity));
      const double actual = luminance(midpoints.at(edgeKey(a, b)).radiosity);
      differ = differ || std::abs(shown(e, actual) - shown(e, interpolated)) > threshold;
    }
    return differ;
  }

  /// Shadow boundaries: light one vertex sees that another does not, showing more than `threshold`.
  bool shadowCrosses(int e, const std::array<int, 3>& corner, double threshold) const {
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const VertexLight &vi = vertices[size_t(corner[i])], &vj = vertices[size_t(corner[j])];
        if (i == j || vi.visible == vj.visible) continue;
        const double lum = luminance(vi.radiosity);
        if (shown(e, lum) - shown(e, lum - lightOnlyFrom(vi, vj, lightOf)) > threshold) return true;
      }
    return false;
  }

  /// A gap's mouth: one corner in the gap, another not.
  bool gapMouth(const std::array<int, 3>& corner) const {
    if (enclosure.empty()) return false;
    const auto [low, high] = std::minmax({enclosure[size_t(corner[0])], enclosure[size_t(corner[1])],
                                          enclosure[size_t(corner[2])]});
    return high >= kInGap && low < kInGap;
  }

  bool operator()(int e) const {
    std::array<int, 3> corner;
    if (longestEdge(mesh, e) <= minElementEdge) {  // under the floor: a sharp change only
      const double sharp = kSharpContrast * contrast;
      return midpointsDiffer(e, corner, sharp) || shadowCrosses(e, corner, sharp);
    }
    return midpointsDiffer(e, corner, contrast) || shadowCrosses(e, corner, contrast) || gapMouth(corner);
  }
};

}  // namespace

std::vector<int> elementsToRefine(const PatchMesh& mesh, DirectLight& light,
                                  const DisplayEstimate& estimate, const AdaptiveOptions& options,
                                  MidpointLight& midpoints, const std::vector<double>& enclosure,
                                  const std::vector<int>* among) {
  std::vector<int> out;
  if (!light.enabled()) return out;
  RAD_CHECK(light.vertices().size() == mesh.mesh.n_vertices());
  const std::vector<int> candidates = refinable(mesh, options, among);
  lightMidpoints(mesh, light, candidates, midpoints);
  const RefineTest needsRefining{mesh, light.vertices(), midpoints, enclosure, lightOfSamples(light), estimate.ambient,
                                 options.exposure > 0 ? options.exposure : estimate.exposure, options.contrast,
                                 options.minElementEdge};
  for (int e : candidates)
    if (needsRefining(e)) out.push_back(e);
  return out;
}

namespace {

/// Bisects the marked elements; each new vertex is the midpoint of the edge it split, where
/// the light is known: that light, by new vertex, moved out of `midpoints`; or, for an edge
/// that had no midpoint probed (made by this round's bisection, or split to keep the mesh
/// conforming), the ends of that edge, by new vertex, in `between`. `changed`: the elements
/// round the new vertices (every other element is as it was). Edges shorter than half the
/// smallest element's (the floor for sharp changes) are left whole: a marked element is longer
/// than that smallest, its halves half as long at least, and only slivers' propagation paths
/// need shorter ones.
std::unordered_map<int, VertexLight> bisect(PatchMesh& mesh, const std::vector<int>& marked, double minElementEdge,
                                            MidpointLight& midpoints, std::vector<int>& changed,
                                            std::unordered_map<int, std::pair<int, int>>& between) {
  std::vector<EdgeSplit> splits;
  bisectElements(mesh, marked, &splits, 0.5 * minElementEdge / kSharpRefinement);
  changed.clear();
  for (const auto& s : splits)
    for (auto f : mesh.mesh.vf_range(TriMesh::VertexHandle(s.vertex))) changed.push_back(f.idx());
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  std::unordered_map<int, VertexLight> known;
  between.clear();
  for (const auto& s : splits) {
    auto it = midpoints.find(edgeKey(s.from, s.to));
    if (it == midpoints.end()) {
      between.emplace(s.vertex, std::make_pair(s.from, s.to));
      continue;
    }
    known.emplace(s.vertex, std::move(it->second));
    midpoints.erase(it);
  }
  return known;
}

/// Extends `enclosure` to every vertex of the mesh (gapReach > 0): the share of each new
/// vertex's short rays that met a surface within gapReach.
void encloseNewVertices(const PatchMesh& mesh, const DirectLight& light, double gapReach,
                        std::vector<double>& enclosure) {
  if (!(gapReach > 0)) return;
  const size_t from = enclosure.size();
  std::vector<double> reach(mesh.mesh.n_vertices(), 0.0);
  std::fill(reach.begin() + std::ptrdiff_t(from), reach.end(), gapReach);
  const std::vector<int> met = light.surfacesWithin(mesh, reach, kGapConeDeg);
  constexpr double rays = kNearbyRaysPerSide * kNearbyRaysPerSide;
  for (size_t v = from; v < met.size(); ++v) enclosure.push_back(met[v] / rays);
}

/// Whether the mesh has reached the element cap (said in the mesh's warnings).
bool capReached(PatchMesh& mesh, const AdaptiveOptions& options) {
  if (options.maxElements <= 0 || mesh.elementCount() < options.maxElements) return false;
  mesh.warnings.push_back("adaptive refinement stopped at " + std::to_string(mesh.elementCount()) +
                          " elements, the cap (raise solver.max_elements)");
  return true;
}

}  // namespace

AdaptiveStats refineAdaptively(PatchMesh& mesh, DirectLight& light, const AdaptiveOptions& options) {
  RAD_CHECK(options.minElementEdge > 0);  // without a floor only maxRounds would stop it
  const auto start = std::chrono::steady_clock::now();
  AdaptiveStats stats;
  stats.elementsBefore = stats.elementsAfter = mesh.elementCount();
  if (!light.enabled()) return stats;
  light.update(mesh);
  std::vector<double> enclosure;
  encloseNewVertices(mesh, light, options.gapReach, enclosure);
  const DisplayEstimate estimate = estimateDisplay(mesh, light);
  MidpointLight midpoints;
  stats.exposure = options.exposure > 0 ? options.exposure : estimate.exposure;
  StageProgress progress("refinement: rounds (at most)", size_t(options.maxRounds));
  // After the first round only the elements bisection changed can be marked: the others'
  // corners and midpoints are as they were, and they were not marked then.
  std::vector<int> changed;
  for (int round = 0; round < options.maxRounds && light.enabled() && !capReached(mesh, options); ++round) {
    progress.update(size_t(round));
    std::vector<int> marked =
        elementsToRefine(mesh, light, estimate, options, midpoints, enclosure, round ? &changed : nullptr);
    if (marked.empty()) break;
    stats.marked += int(marked.size());
    std::unordered_map<int, std::pair<int, int>> between;
    std::unordered_map<int, VertexLight> known = bisect(mesh, marked, options.minElementEdge, midpoints, changed, between);
    light.update(mesh, &known, &between);
    encloseNewVertices(mesh, light, options.gapReach, enclosure);
    ++stats.rounds;
  }
  stats.elementsAfter = mesh.elementCount();
  if (stats.rounds > 0) updateMeshStats(mesh);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace rad
