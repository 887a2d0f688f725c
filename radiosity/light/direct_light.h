#pragma once
// Direct light at the mesh's vertices by rays to fixed sample points on the emitters
// (Wallace, Elmquist & Haines 1989), so that shadow boundaries do not depend on the hemicube
// resolution, and the visibility facts adaptive refinement decides by.
#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"

namespace rad {

class ClearSight;
class ElementHierarchy;

/// Sample points per emitting surface side (at most kMaxLightSamples over all): each emitting
/// patch gets its share by area (at least one), spread over it in strata of equal area
/// (patchSamples).
constexpr int kDefaultLightSamples = 512;
/// At most this many samples over all emitting surface sides (rays per vertex): with many
/// glowing surfaces each gets fewer.
constexpr int kMaxLightSamples = 4096;
/// Rays per point that its lights share by what each brings (its unoccluded factor times its
/// emission): each light is seen through every stride-th of its samples, the stride the
/// largest power of two that leaves kRaysPerPoint times its share of them, and at least
/// kMinRaysPerLight. A lone light (the Cornell box) casts every sample.
constexpr int kRaysPerPoint = kDefaultLightSamples;
constexpr int kMinRaysPerLight = 16;
/// Above this many emitting patches, direct light by rays costs more than it brings (a scene
/// where most surfaces glow has no sharp shadows): the hemicubes' values are shown instead.
constexpr int kMaxRayEmitterPatches = 256;
/// A light a point would cast at least this many rays to is first tested whole (ClearSight):
/// when nothing stands between them, every sample is visible and no ray is cast.
constexpr int kClearSightRays = 32;
/// DirectLight::surfacesWithin casts this many squared short rays from a vertex.
constexpr int kNearbyRaysPerSide = 4;

/// The most emitting patches a mesh of the scene with elements of at most `elementEdge` may
/// have, about, before it is meshed: every emitting polygon side a patch per element, its area
/// over kLeastElementArea·elementEdge², and at least one per polygon. Above
/// kMaxRayEmitterPatches, rays may not follow, and the mesher grades the contact lines itself.
double mostEmittingPatches(const Scene& scene, double elementEdge);
/// A quality mesh's mean element area, in elementEdge², a little below what is measured: the
/// uniform meshes of the shipped scenes' emitters come out at 0.174–0.199 (the Cornell box's
/// light 0.174, the cube's ceiling 0.196); graded contact lines make elements smaller.
constexpr double kLeastElementArea = 0.15;

/// One emitting patch seen from the vertices: its outline (counter-clockwise seen from its
/// lit side) and the outlines of its holes (wound the other way; loops through a vertex where
/// the patch is pinched); and its samples [first, first + count). A patch round a hole is one
/// light: the lights share a point's rays light by light, so it costs what one light does.
struct LightPolygon {
  std::vector<std::vector<glm::dvec3>> outlines;
  /// The outlines' convex hull, and the same moved off the emitter halfway to the ray ends:
  /// every ray to the light's samples lies in the hull of its start and this (ClearSight).
  std::vector<glm::dvec3> hull, rayHull;
  double size = 0;  ///< the hull's diameter
  glm::dvec3 normal{0.0}, emission{0.0};
  int first = 0, count = 0;
};

/// The direct light at one vertex: ρ·Σₜ Eₜ·Fₜ·(visible share of t's samples), Fₜ the exact
/// unoccluded point-to-polygon factor of light t; and, per sample, whether it is visible.
struct VertexLight {
  glm::dvec3 radiosity{0.0};
  std::vector<uint64_t> visible;  ///< bit per sample
  std::vector<float> weight;      ///< per light: luminance each visible sample adds
};

/// Rays against every element of the mesh (Embree, single precision in coordinates
/// normalised to the scene's box). The mesh may be refined afterwards (bisection does not
/// move geometry): update() computes the vertices added since.
class DirectLight {
 public:
  /// raysPerPoint: what the lights share at a point (kRaysPerPoint; as many as the samples:
  /// every sample of every light). workers: threads casting rays (0: one per hardware thread).
  DirectLight(const PatchMesh& mesh, double sceneSize, int samplesPerEmitter = kDefaultLightSamples,
              int raysPerPoint = kRaysPerPoint, int workers = 0);
  ~DirectLight();
  DirectLight(const DirectLight&) = delete;
  DirectLight& operator=(const DirectLight&) = delete;

  /// Whether the scene's emitters are few enough for rays (kMaxRayEmitterPatches).
  bool enabled() const { return enabled_; }
  /// Computes the vertices of `mesh` (the same mesh, perhaps refined) not yet computed;
  /// those in `known` (by vertex index) are taken from there (moved out); those in `between`
  /// lie midway between two vertices (the ends of the edge bisection split) and are probed
  /// given what those see, as a midpoint is (Probe::visible), once their light is known.
  void update(const PatchMesh& mesh, std::unordered_map<int, VertexLight>* known = nullptr,
              const std::unordered_map<int, std::pair<int, int>>* between = nullptr);
  const std::vector<VertexLight>& vertices() const { return vertices_; }
  const std::vector<LightPolygon>& lights() const { return lights_; }
  int samples() const { return samples_; }
  long rays() const { return rays_; }
  /// Lights seen whole by clear sight, without a ray (summed over the points).
  long seenWhole() const { return seenWhole_; }
  /// Per vertex, the direct light (radiosity).
  std::vector<glm::dvec3> radiosity() const;
  /// Per vertex of `mesh` with reach[v] > 0: how many of kNearbyRaysPerSide² short rays
  /// (cosine-weighted within coneDeg of its normal, reach[v] long, from where its light is
  /// looked for) meet a surface (any element: its own surface's too, where that bends towards
  /// it); 0 for the others, and for a vertex no face uses or whose normal is not of unit
  /// length (its faces cancel out): it has no side to look from.
  std::vector<int> surfacesWithin(const PatchMesh& mesh, const std::vector<double>& reach,
                                  double coneDeg = 90) const;

  /// A point to find the direct light at: on a surface with unit normal `normal` and
  /// reflectance `rho`; rays start a little off it, towards `inwards` (its own elements).
  struct Probe {
    glm::dvec3 point{0.0}, normal{0.0}, rho{0.0}, inwards{0.0};
    /// The size of the elements round the point (0: unknown): rays start closer to the
    /// surface where elements are small, so that they do not start past small occluders.
    double size = 0;
    /// If set, the samples visible from the point are taken to be these, and no ray is cast
    /// (between two vertices that see the same samples).
    const std::vector<uint64_t>* visible = nullptr;
    /// If set too, the samples seen from the two ends of an edge the point lies between:
    /// a sample both ends see, or neither, is taken as they have it, and rays are cast to the
    /// others only (the shadow's edge crosses the light between them).
    const std::vector<uint64_t>* alsoVisible = nullptr;
    /// Whether to look for a clear sight of each light before casting rays (ClearSight); a
    /// probe given `visible` looks only where its ends differ in at least kClearSightRays
    /// samples (an edge across a whole penumbra: its rays would go into the penumbra, where a
    /// clear sight is seldom found, but past it too).
    bool clearSight = true;
  };
  /// The direct light at each probe, on all workers.
  std::vector<VertexLight> lightAt(const std::vector<Probe>& probes);

 private:
  /// Adds the light(s) of emitting patch `p` with `count` samples.
  void addLight(const PatchMesh& mesh, int p, int count);
  /// Adds a sample point on a light with unit normal `normal`.
  void addSample(const glm::dvec3& at, const glm::dvec3& normal);
  /// Whether each of the samples is visible from `origin` (given by the probe, or by rays).
  void samplesVisible(const Probe& probe, const glm::dvec3& origin, const std::vector<int>& samples,
                      std::vector<char>& visible, long& raysCast) const;
  struct SeenLight;
  /// Light t's exact unoccluded factor from p with normal n (0 behind it).
  double unoccludedFactor(const glm::dvec3& p, const glm::dvec3& n, size_t t) const;
  /// Whether light t lies wholly above the horizon of p with normal n, p wholly in front of it.
  bool whollyAbove(const glm::dvec3& p, const glm::dvec3& n, size_t t) const;
  /// The light at a probe given what it sees (and no second end), into `out`, when it sees
  /// each light above its horizon whole or not at all; false (out untouched) otherwise.
  bool fromEnds(const Probe& probe, const glm::dvec3& p, VertexLight& out) const;
  /// Light t seen from p with normal n into `out`: its samples above the horizon, none tested
  /// yet.
  void samplesAbove(const glm::dvec3& p, const glm::dvec3& n, size_t t, SeenLight& out) const;
  /// The visible share of light t's weight from p with normal n (weighing its samples if it
  /// is seen in part).
  double seenShare(const glm::dvec3& p, const glm::dvec3& n, size_t t, SeenLight& light) const;
  /// Tests every stride-th of the light's samples from p (those not tested yet), unless it
  /// was tested as finely already.
  void test(const Probe& probe, const glm::dvec3& p, size_t stride, SeenLight& light, long& raysCast) const;
  /// The direct light at one probe, counting the rays it casts and the lights it sees whole.
  VertexLight compute(const Probe& probe, long& raysCast, long& seenWhole) const;

  struct Rays;
  std::unique_ptr<Rays> rays_impl_;
  std::unique_ptr<ElementHierarchy> occluders_;  // the elements, for clearSight_
  std::unique_ptr<ClearSight> clearSight_;
  std::vector<LightPolygon> lights_;
  std::vector<glm::dvec3> onLight_;  // sample points
  std::array<std::vector<double>, 3> onLightAxes_;  // the same, axis by axis (weights, in runs)
  std::vector<glm::dvec3> points_;   // the same, moved off their emitter: where rays end
  std::vector<VertexLight> vertices_;
  double sceneSize_ = 1;
  int samples_ = 0, raysPerPoint_ = kRaysPerPoint, workers_ = 1;
  bool enabled_ = false;
  long rays_ = 0, seenWhole_ = 0;
};

/// The probe of mesh vertex v: its point, normal and reflectance, towards the centroid of its
/// elements, sized by its shortest edge.
DirectLight::Probe vertexProbe(const PatchMesh& mesh, TriMesh::VertexHandle v);

/// Where light at a probe is evaluated: a little off the surface and inwards. A point on a
/// surface's edge shows the limit from inside the surface (a floor point at the foot of a
/// glowing wall sees half its hemisphere filled by it, not the wall edge-on).
glm::dvec3 offSurface(const DirectLight::Probe& probe, double sceneSize);

}  // namespace rad
