// Direct light ▸ the probes: where a vertex's light is looked for (a little off its surface,
// inwards), and update()'s rounds: new vertices on their own, then those between the two ends
// bisection split once the ends' light is known.
#include "radiosity/light/direct_light.h"

#include <algorithm>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "radiosity/light/direct_light_internal.h"

namespace rad {
namespace {

/// Near small elements the receiver's offset shrinks to this share of their size, but not
/// below kMinRayOffset of the scene size (single-precision rays in coordinates normalised to
/// the scene: about 17 units in the last place).
constexpr double kRayOffsetOfElement = 1e-3;
constexpr double kMinRayOffset = 1e-6;
/// A probe's inwards shorter than this (relative to the scene size) is rounding, no direction.
constexpr double kNoDirection = 1e-9;

/// Whether vertex v's light was skipped as black (compute: a probe of reflectance 0).
bool blackVertex(const PatchMesh& mesh, int v) {
  for (auto f : mesh.mesh.vf_range(TriMesh::VertexHandle(v))) return mesh.reflectance(f.idx()) == glm::dvec3(0.0);
  return true;
}

}  // namespace

DirectLight::Probe vertexProbe(const PatchMesh& mesh, TriMesh::VertexHandle v) {
  DirectLight::Probe probe;
  probe.point = PatchMesh::toGlm(mesh.mesh.point(v));
  probe.normal = PatchMesh::toGlm(mesh.mesh.normal(v));
  int faces = 0;
  for (auto f : mesh.mesh.vf_range(v)) {
    if (faces++ == 0) probe.rho = mesh.reflectance(f.idx());
    probe.inwards += mesh.centroid(f.idx());
  }
  for (auto w : mesh.mesh.vv_range(v)) {
    const double edge = (mesh.mesh.point(w) - mesh.mesh.point(v)).norm();
    probe.size = probe.size > 0 ? std::min(probe.size, edge) : edge;
  }
  if (faces) probe.inwards = probe.inwards / double(faces) - probe.point;
  return probe;
}

glm::dvec3 offSurface(const DirectLight::Probe& probe, double sceneSize) {
  double offset = direct_light::kRayOffset * sceneSize;
  if (probe.size > 0)
    offset = std::clamp(kRayOffsetOfElement * probe.size, kMinRayOffset * sceneSize, offset);
  // Inwards along the surface only; a vertex amid its elements has their centroids all round
  // it, and what is left of their sum is rounding, no direction (along the normal it would
  // cancel the offset off the surface: the rays would start in it and see nothing).
  const glm::dvec3 along = probe.inwards - probe.normal * glm::dot(probe.inwards, probe.normal);
  const double inwards = glm::length(along);
  return probe.point + probe.normal * offset +
         (inwards > kNoDirection * sceneSize ? along * (offset / inwards) : glm::dvec3(0.0));
}

void DirectLight::update(const PatchMesh& mesh, std::unordered_map<int, VertexLight>* known,
                         const std::unordered_map<int, std::pair<int, int>>* between) {
  if (!enabled_) return;
  const size_t from = vertices_.size(), to = mesh.mesh.n_vertices();
  if (from >= to) return;
  vertices_.resize(to);
  std::vector<char> done(to - from, 0);  // per new vertex
  auto isDone = [&](int v) { return size_t(v) < from || done[size_t(v) - from]; };
  std::vector<size_t> waiting;  // vertices between two ends, waiting for those
  std::vector<Probe> probes;
  std::vector<size_t> at;
  for (size_t k = from; k < to; ++k) {
    if (known) {
      auto it = known->find(int(k));
      if (it != known->end()) {
        vertices_[k] = std::move(it->second);
        done[k - from] = 1;
        continue;
      }
    }
    if (between && between->count(int(k))) {
      waiting.push_back(k);
      continue;
    }
    probes.push_back(vertexProbe(mesh, TriMesh::VertexHandle(int(k))));
    at.push_back(k);
  }
  // Rounds: the vertices on their own first, then those whose ends are known by then (an end
  // may itself be a vertex bisection put between two others).
  while (true) {
    if (!probes.empty()) {
      std::vector<VertexLight> found = lightAt(probes);
      for (size_t i = 0; i < at.size(); ++i) vertices_[at[i]] = std::move(found[i]), done[at[i] - from] = 1;
      probes.clear(), at.clear();
    }
    if (waiting.empty()) break;
    std::vector<size_t> still;
    for (size_t k : waiting) {
      const auto [a, b] = between->at(int(k));
      if (!isDone(a) || !isDone(b)) {
        still.push_back(k);
        continue;
      }
      Probe probe = vertexProbe(mesh, TriMesh::VertexHandle(int(k)));
      // A black end saw nothing, tested or not: what its samples say is no visibility.
      if (blackVertex(mesh, a) || blackVertex(mesh, b)) {
        probes.push_back(probe);
        at.push_back(k);
        continue;
      }
      probe.visible = &vertices_[size_t(a)].visible;
      if (vertices_[size_t(b)].visible != *probe.visible) probe.alsoVisible = &vertices_[size_t(b)].visible;
      probes.push_back(probe);
      at.push_back(k);
    }
    if (probes.empty()) {  // ends that never come (not vertices bisection made): on their own
      for (size_t k : still) probes.push_back(vertexProbe(mesh, TriMesh::VertexHandle(int(k)))), at.push_back(k);
      still.clear();
    }
    waiting = std::move(still);
  }
}

std::vector<glm::dvec3> DirectLight::radiosity() const {
  std::vector<glm::dvec3> out;
  out.reserve(vertices_.size());
  for (const auto& v : vertices_) out.push_back(v.radiosity);
  return out;
}

}  // namespace rad
