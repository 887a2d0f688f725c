#include "radiosity/shooting/shooter_clusters.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>

#include "mesh/patch_mesh.h"

namespace rad {
namespace {

/// Normals and plane offsets equal to this (offsets relative to the scene's extent) make one
/// plane: far below the hemicube's eye offset (1e-6 of the scene). A cluster's hemicubes
/// leave its own elements out all the same.
constexpr double kSamePlane = 1e-9;

using PlaneKey = std::tuple<int, int, long long, long long, long long, long long>;

/// Where plane offsets are measured from and at what scale: the low corner of the patches'
/// centroids, and their extent plus the widest patch (so that offsets stay within about one
/// extent, whatever the scene's distance from its origin).
struct Extent {
  glm::dvec3 corner{0.0};
  double size = 1;
};

Extent sceneExtent(const PatchMesh& mesh) {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  double widest = 0;
  for (const Patch& p : mesh.patches) {
    lo = glm::min(lo, p.centroid);
    hi = glm::max(hi, p.centroid);
    widest = std::max(widest, p.diameter);
  }
  if (mesh.patches.empty()) return {};
  return {lo, std::max(glm::length(hi - lo) + widest, 1e-300)};
}

PlaneKey planeKey(const Patch& p, const Extent& extent) {
  auto q = [](double x) { return (long long)std::llround(x / kSamePlane); };
  const double offset = glm::dot(p.normal, p.centroid - extent.corner) / extent.size;
  return {p.surface, p.side, q(p.normal.x), q(p.normal.y), q(p.normal.z), q(offset)};
}

/// A unit vector perpendicular to n.
glm::dvec3 perpendicular(const glm::dvec3& n) {
  const glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(n, a));
}

}  // namespace

ShooterClusters::ShooterClusters(const PatchMesh& mesh, int maxPatches) : mesh_(mesh) {
  above_.assign(mesh.patches.size(), -1);
  const Extent extent = sceneExtent(mesh);
  std::map<PlaneKey, std::vector<int>> planes;
  for (int p = 0; p < int(mesh.patches.size()); ++p)
    if (!mesh.emits(p)) planes[planeKey(mesh.patches[p], extent)].push_back(p);
  for (auto& [key, patches] : planes) bisect(std::move(patches), maxPatches);
}

int ShooterClusters::bisect(std::vector<int> patches, int maxPatches) {
  if (patches.size() < 2) return -1;
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (int p : patches) {
    lo = glm::min(lo, mesh_.patches[p].centroid);
    hi = glm::max(hi, mesh_.patches[p].centroid);
  }
  const glm::dvec3 span = hi - lo;
  const int axis = span.x >= span.y && span.x >= span.z ? 0 : span.y >= span.z ? 1 : 2;
  std::stable_sort(patches.begin(), patches.end(), [&](int a, int b) {
    return mesh_.patches[a].centroid[axis] < mesh_.patches[b].centroid[axis];
  });
  const auto middle = patches.begin() + long(patches.size() / 2);
  const int first = bisect(std::vector<int>(patches.begin(), middle), maxPatches);
  const int second = bisect(std::vector<int>(middle, patches.end()), maxPatches);
  if (int(patches.size()) > maxPatches) return -1;
  const int self = record(std::move(patches));
  for (int child : {first, second})
    if (child >= 0) clusters_[size_t(child)].parent = self;
  return self;
}

int ShooterClusters::record(std::vector<int> patches) {
  const int id = int(clusters_.size());
  ShooterCluster c;
  const Patch& head = mesh_.patches[patches.front()];
  c.normal = head.normal;
  c.origin = head.centroid;
  c.u = perpendicular(c.normal);
  c.v = glm::cross(c.normal, c.u);
  c.uLo = c.vLo = HUGE_VAL;
  c.uHi = c.vHi = -HUGE_VAL;
  double span = 0;
  for (int p : patches) {
    // Children are recorded first: the first cluster to take a patch is its smallest.
    if (above_[size_t(p)] < 0) above_[size_t(p)] = id;
    const Patch& patch = mesh_.patches[p];
    c.area += patch.area;
    span = std::max(span, patch.diameter);
    for (int e : patch.elements) {
      c.elements.push_back(e);
      for (const glm::dvec3& x : mesh_.corners(e)) {
        const double a = glm::dot(x - c.origin, c.u), b = glm::dot(x - c.origin, c.v);
        c.uLo = std::min(c.uLo, a), c.uHi = std::max(c.uHi, a);
        c.vLo = std::min(c.vLo, b), c.vHi = std::max(c.vHi, b);
      }
    }
  }
  c.diameter = std::max(span, std::hypot(c.uHi - c.uLo, c.vHi - c.vLo));
  c.patches = std::move(patches);
  clusters_.push_back(std::move(c));
  return id;
}

}  // namespace rad
