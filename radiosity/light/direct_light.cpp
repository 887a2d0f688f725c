// Direct light ▸ the lights: every emitting patch a light polygon with its samples (strata of
// equal area), and the occluders the rays and the clear-sight test look at.
#include "radiosity/light/direct_light.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "mesh/base/parallel.h"
#include "mesh/scene/geometry.h"
#include "radiosity/formfactors/element_hierarchy.h"
#include "radiosity/light/clear_sight.h"
#include "radiosity/light/direct_light_internal.h"
#include "radiosity/shooting/shooter_samples.h"

namespace rad {
namespace {

/// The outline of a patch (PatchMesh::boundaryLoops) as points. Lambert's contour sum over
/// the loops is the patch's, pinched or not, as it is a sum over the boundary's edges.
std::vector<std::vector<glm::dvec3>> patchLoops(const PatchMesh& mesh, const Patch& patch) {
  const int id = mesh.patch(patch.elements[0]);
  std::vector<std::vector<glm::dvec3>> loops;
  for (const auto& loop : mesh.boundaryLoops(patch.elements, [&](int e) { return mesh.patch(e) == id; })) {
    std::vector<glm::dvec3>& points = loops.emplace_back();
    for (int v : loop) points.push_back(PatchMesh::toGlm(mesh.mesh.point(TriMesh::VertexHandle(v))));
  }
  return loops;
}

/// An element closer than this (relative to the scene size) to the space between a point and
/// a light may block a single-precision ray (rounding of origin, direction and corners in
/// coordinates normalised to the scene): the light is not taken to be clear. Below
/// kMinRayOffset, so that the surface a point lies on stays apart.
constexpr double kClearSightMargin = 3e-7;

/// The emitting patches, and per surface side (surface·2 + side) their area.
std::vector<int> emittingPatches(const PatchMesh& mesh, std::vector<double>& sideArea) {
  std::vector<int> emitters;
  sideArea.assign(mesh.surfaces.size() * 2, 0.0);
  for (int p = 0; p < int(mesh.patches.size()); ++p) {
    if (!mesh.emits(p)) continue;
    emitters.push_back(p);
    sideArea[size_t(mesh.patches[p].surface * 2 + mesh.patches[p].side)] += mesh.patches[p].area;
  }
  return emitters;
}

}  // namespace

double mostEmittingPatches(const Scene& scene, double elementEdge) {
  const double elementArea = kLeastElementArea * elementEdge * elementEdge;
  double patches = 0;
  for (const Surface& s : scene.surfaces) {
    if (!scene.materials[s.material].emits()) continue;
    const double sides = s.twoSided ? 2 : 1;
    for (const Polygon& p : s.polygons) patches += sides * std::max(1.0, polygonArea(p) / elementArea);
  }
  return patches;
}

DirectLight::DirectLight(const PatchMesh& mesh, double sceneSize, int samplesPerEmitter, int raysPerPoint,
                         int workers)
    : rays_impl_(std::make_unique<Rays>()), sceneSize_(sceneSize), raysPerPoint_(raysPerPoint),
      workers_(workerCount(workers)) {
  // The lights: every emitting patch, with samples by its share of its surface side.
  std::vector<double> sideArea;
  const std::vector<int> emitters = emittingPatches(mesh, sideArea);
  enabled_ = !emitters.empty() && int(emitters.size()) <= kMaxRayEmitterPatches;
  if (!enabled_) return;
  // Many glowing surfaces share one budget of samples (rays per vertex).
  const int sides = int(std::count_if(sideArea.begin(), sideArea.end(), [](double a) { return a > 0; }));
  samplesPerEmitter = std::max(1, std::min(samplesPerEmitter, kMaxLightSamples / sides));
  for (int p : emitters) {
    const Patch& patch = mesh.patches[p];
    const double share = patch.area / sideArea[size_t(patch.surface * 2 + patch.side)];
    addLight(mesh, p, std::max(1, int(std::lround(samplesPerEmitter * share))));
  }
  samples_ = int(points_.size());
  // The occluders: every element, for the rays and for the clear-sight test.
  rays_impl_->build(mesh);
  std::vector<glm::dvec3> positions, normals;
  std::vector<uint32_t> indices;
  for (auto v : mesh.mesh.vertices()) positions.push_back(PatchMesh::toGlm(mesh.mesh.point(v)));
  for (auto f : mesh.mesh.faces()) {
    for (auto v : mesh.mesh.fv_range(f)) indices.push_back(uint32_t(v.idx()));
    // Each triangle's own plane (a piece's plane is a best fit, its corners within kPlanarity
    // of it): the clear-sight test separates by it.
    const size_t i = indices.size() - 3;
    const glm::dvec3 a = positions[indices[i]];
    const glm::dvec3 n = glm::cross(positions[indices[i + 1]] - a, positions[indices[i + 2]] - a);
    normals.push_back(glm::length(n) > 0 ? glm::normalize(n) : PatchMesh::toGlm(mesh.mesh.normal(f)));
  }
  occluders_ = std::make_unique<ElementHierarchy>(positions, indices, normals);
  clearSight_ = std::make_unique<ClearSight>(*occluders_, kClearSightMargin * sceneSize_);
}

void DirectLight::addSample(const glm::dvec3& at, const glm::dvec3& normal) {
  onLight_.push_back(at);
  for (int a = 0; a < 3; ++a) onLightAxes_[size_t(a)].push_back(at[a]);
  points_.push_back(at + normal * (direct_light::kRayOffset * sceneSize_));
}

void DirectLight::addLight(const PatchMesh& mesh, int p, int count) {
  const Patch& patch = mesh.patches[p];
  LightPolygon light;
  light.normal = patch.normal;
  light.emission = mesh.emission(patch.elements[0]);
  light.first = int(points_.size());
  // Strata of equal area, neighbours in order, over the whole patch (a ring round its hole
  // too): a tested sample stands for the stride of them after it.
  for (const ShooterSample& s : patchSamples(mesh, p, count)) addSample(s.point, light.normal);
  light.count = int(points_.size()) - light.first;
  light.outlines = patchLoops(mesh, patch);
  if (light.outlines.empty())  // no closed loops: the elements' outlines
    for (int e : patch.elements) {
      const auto c = mesh.corners(e);
      light.outlines.emplace_back(c.begin(), c.end());
    }
  std::vector<glm::dvec3> corners;
  for (const auto& o : light.outlines) corners.insert(corners.end(), o.begin(), o.end());
  const PlaneFrame frame = planeFrame(corners[0], light.normal);
  std::vector<glm::dvec2> projected;
  for (const glm::dvec3& c : corners) projected.push_back(frame.project(c));
  for (size_t k : convexHull(projected)) light.hull.push_back(corners[k]);
  light.rayHull = light.hull;
  light.size = ringDiameter(light.hull);
  // The pyramid's base halfway between the emitter and the ray ends: it holds every ray
  // whole, and the emitter's own elements stay well outside it.
  for (glm::dvec3& corner : light.rayHull) corner += light.normal * (0.5 * direct_light::kRayOffset * sceneSize_);
  lights_.push_back(std::move(light));
}

DirectLight::~DirectLight() = default;

}  // namespace rad
