#pragma once
// The scene as the path tracer sees it: the surfaces' own polygons, triangulated here (ear
// clipping; holes are left out of every hit and light sample by a point-in-ring test), in
// coordinates normalised to the scene's box, with rays through Embree. Nothing here comes from
// the patch mesh or the hemicube solver: the reference shares only the scene loader with them.
#include <cstddef>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mesh/scene/scene.h"

namespace rad::pathtrace {

/// Rays start this far (normalised units: the scene's size is 1) off their surface: about 170
/// units in the last place of the single-precision coordinates Embree sees.
constexpr double kRayOffset = 1e-5;
/// Surfaces in one plane are put this far apart (normalised units): four units in the last
/// place of the single-precision coordinates near the scene's edge; at most kMaxCoplanarSteps
/// of them (1.9e-6), well inside kRayOffset.
constexpr double kCoplanarStep = 2.4e-7;
constexpr size_t kMaxCoplanarSteps = 8;

/// One triangle of a surface polygon, in normalised coordinates.
struct TraceTriangle {
  glm::dvec3 a{0.0}, b{0.0}, c{0.0};
  glm::dvec3 normal{0.0};  ///< unit, towards the lit (front) side
  double area = 0;
  int surface = -1;
  int holes = -1;  ///< index of its polygon's holes (TraceScene::HoleSet), -1 for none
};

/// What a ray hit: the triangle, the point on it and which of its sides faces the ray.
struct TraceHit {
  int triangle = -1;
  glm::dvec3 point{0.0};
  bool front = false;
};

/// A point on an emitter, chosen with probability density `pdf` per unit (normalised) area.
struct LightSample {
  glm::dvec3 point{0.0}, normal{0.0}, emission{0.0};
  double pdf = 0;
  bool twoSided = false;
};

class TraceScene {
 public:
  /// Triangulates every polygon of the scene and builds the ray-casting structure. The scene
  /// must outlive it (materials are read from it).
  explicit TraceScene(const Scene& scene);
  explicit TraceScene(Scene&&) = delete;  ///< a temporary scene would die before the tracer
  ~TraceScene();
  TraceScene(const TraceScene&) = delete;
  TraceScene& operator=(const TraceScene&) = delete;

  /// Scene coordinates to normalised ones ((p − centre) / size) and back.
  glm::dvec3 toLocal(const glm::dvec3& p) const { return (p - centre_) / size_; }
  glm::dvec3 toScene(const glm::dvec3& p) const { return p * size_ + centre_; }
  double size() const { return size_; }

  const Scene& scene() const { return scene_; }
  const std::vector<TraceTriangle>& triangles() const { return triangles_; }
  const TraceTriangle& triangle(int t) const { return triangles_[size_t(t)]; }
  const Material& material(int surface) const;
  bool twoSided(int surface) const { return scene_.surfaces[size_t(surface)].twoSided; }

  /// The nearest hit along origin + t·direction, 0 < t < tFar (normalised coordinates);
  /// triangle −1 when nothing is hit.
  TraceHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double tFar) const;
  /// Whether anything lies on the open segment from `from` to `to`.
  bool occluded(const glm::dvec3& from, const glm::dvec3& to) const;
  /// Whether the side a ray hit reflects: its front, or either side of a two-sided surface
  /// (the back of a one-sided surface absorbs).
  bool reflects(const TraceHit& hit) const {
    return hit.front || twoSided(triangle(hit.triangle).surface);
  }
  /// The unit normal of the side a ray hit.
  glm::dvec3 sideNormal(const TraceHit& hit) const {
    return hit.front ? triangle(hit.triangle).normal : -triangle(hit.triangle).normal;
  }
  /// Whether point p (on triangle t's plane) lies in one of its polygon's holes.
  bool inHole(int t, const glm::dvec3& p) const;

  /// Whether the scene has any emitter.
  bool emits() const { return !lightCdf_.empty(); }
  /// A point on the emitters, the triangle chosen by power (area × emission summed over
  /// channels), uniform on it; u in [0, 1)³. A point in a hole has no emission.
  LightSample sampleLight(double u0, double u1, double u2) const;
  /// The density per unit (normalised) area with which sampleLight picks points of
  /// triangle t (0 for a triangle that does not emit).
  double lightPdf(int t) const { return lightPdf_[size_t(t)]; }
  /// A uniform point on triangle t for u0, u1 in [0, 1).
  glm::dvec3 pointOn(int t, double u0, double u1) const;

  /// A polygon's holes in its own plane frame.
  struct HoleSet {
    glm::dvec3 origin{0.0}, u{0.0}, v{0.0};
    std::vector<std::vector<glm::dvec2>> rings;
  };

 private:
  /// Sets centre_ and size_ from the box of the surfaces' outer rings.
  void fitBox();
  /// The ring in normalised coordinates, without repeated corners or a closing repeat.
  std::vector<glm::dvec3> localRing(const Ring& outer) const;
  /// Triangulates one polygon (normalised coordinates) into triangles_.
  void addPolygon(const Polygon& polygon, int surface);
  /// Adds the triangle (corners, surface, holes set) with its area and unit normal, unless
  /// it has no area.
  void addTriangle(TraceTriangle tri);
  /// Surfaces lying on each other in one plane, facing one way (a rug on a floor, a duplicated
  /// face): the one in front must win the ray, not whichever Embree meets first. As the mesher
  /// decides (mesh/coplanar_pieces.cpp, written independently): the smaller surface lies on the
  /// larger, and of two alike the later in the file. A surface is moved back along its normal
  /// kCoplanarStep for each in front of it in its plane whose box there meets its own.
  void orderCoplanar();
  /// Adds the polygon's holes in its plane frame (origin, u, v) to holes_; returns their index.
  int addHoles(const Polygon& polygon, const glm::dvec3& origin, const glm::dvec3& u,
               const glm::dvec3& v);
  /// Triangle t's emitted power: area × emission summed over channels, twice for two sides.
  double emittedPower(size_t t) const;
  /// The emitters' table: lightTriangle_, lightCdf_ and lightPdf_.
  void buildLights();
  /// lightPdf_ from lightTriangle_ and lightCdf_.
  void fillLightPdf();
  /// The emitter triangle whose share of the power holds u in [0, 1).
  int lightTriangle(double u) const;
  /// Embree's device and an empty robust scene, in rays_.
  void newRays();
  /// Embree's device and scene, holding every triangle.
  void buildRays();
  /// Attaches triangles[global[i]] as Embree geometry `id` (1: with the hole filter).
  void attachGeometry(unsigned id, const std::vector<int>& global);
  /// The hit on `triangle` at Embree's barycentric (u, v), seen along `direction`.
  TraceHit hitOn(int triangle, float u, float v, const glm::dvec3& direction) const;

  const Scene& scene_;
  glm::dvec3 centre_{0.0};
  double size_ = 1;
  std::vector<TraceTriangle> triangles_;
  std::vector<HoleSet> holes_;
  std::vector<int> lightTriangle_;
  std::vector<double> lightCdf_;  // cumulative power, normalised to end at 1
  std::vector<double> lightPdf_;  // per triangle
  struct Rays;
  std::unique_ptr<Rays> rays_;
};

}  // namespace rad::pathtrace
