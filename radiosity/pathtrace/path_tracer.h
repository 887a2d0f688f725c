#pragma once
// The independent reference: radiosity at surface points by Monte Carlo path tracing of the
// diffuse scene (Kajiya 1986; next-event estimation on the emitters chosen by power,
// cosine-weighted bounces, Russian roulette), with its standard error. The back of a one-sided
// surface absorbs, as in the solver; a two-sided surface reflects and emits on both sides.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/base/random.h"
#include "radiosity/pathtrace/trace_scene.h"

namespace rad::pathtrace {

/// A point on one side of a surface, in scene coordinates; `normal` points to that side.
struct SurfacePoint {
  glm::dvec3 position{0.0}, normal{0.0};
  int surface = -1;
  std::string tag;
};

/// B at a point: the mean over paths, its standard error and the number of paths.
struct PointEstimate {
  glm::dvec3 B{0.0}, standardError{0.0};
  long paths = 0;
};

/// Paths per point are traced in batches of this many (the stopping rule is checked between).
constexpr long kPathBatch = 1024;
/// With a relative-error target, at least this many paths per point (so that the variance
/// estimate behind the stopping rule is itself sound).
constexpr long kDefaultMinPaths = 8192;
/// ... and at most this many (a point lit only through a crack converges slowly).
constexpr long kDefaultMaxPaths = 20'000'000;
/// Bounces before Russian roulette may end a path.
constexpr int kRouletteDepth = 3;

struct TraceOptions {
  uint64_t seed = 1;
  long paths = 0;              ///< > 0: exactly this many paths per point
  double relativeError = 0.01;  ///< else: stop when every channel's SE / B is below this
  long minPaths = kDefaultMinPaths, maxPaths = kDefaultMaxPaths;
  int workers = 0;  ///< threads (0: one per hardware thread)
  /// Called with the share of points done, from the calling thread: at the start, after each
  /// point the calling thread traced (it is one of the workers), and at the end.
  std::function<void(double)> progress;
};

class PathTracer {
 public:
  explicit PathTracer(const TraceScene& scene) : scene_(scene) {}

  /// One path's estimate of B at p (normalised coordinates, unit normal n, on `surface`).
  glm::dvec3 tracePath(const glm::dvec3& p, const glm::dvec3& n, int surface, Random& rng) const;

  /// B at one point; `stream` picks the random stream (deterministic for seed and stream).
  PointEstimate estimate(const SurfacePoint& point, uint64_t stream, const TraceOptions& options) const;

  /// B at every point, on all workers; point i uses stream i, so the result does not depend
  /// on the number of workers.
  std::vector<PointEstimate> estimate(const std::vector<SurfacePoint>& points,
                                      const TraceOptions& options) const;

  /// Paths traced so far by this tracer (all calls).
  long pathsTraced() const { return traced_; }

 private:
  /// One bounce of a path at x (unit normal nx, throughput T): the light arriving there
  /// added to B, then x, nx and T moved to where the cosine-weighted bounce lands. False when
  /// the path ends (it escaped, or landed on the back of a one-sided surface).
  bool bounce(glm::dvec3& x, glm::dvec3& nx, glm::dvec3& T, Random& rng, glm::dvec3& B) const;
  /// Next-event estimation at x (unit normal nx): light from a point on the emitters chosen
  /// by power, weighted by the power heuristic against the bounce, added to B with throughput T.
  void addLightSample(const glm::dvec3& x, const glm::dvec3& nx, const glm::dvec3& T, Random& rng,
                      glm::dvec3& B) const;
  /// The emission where the bounce from x along w landed (hit), weighted by the power
  /// heuristic against next-event estimation, added to B with throughput T.
  void addBounceEmission(const glm::dvec3& x, const glm::dvec3& nx, const glm::dvec3& w,
                         const TraceHit& hit, const glm::dvec3& T, glm::dvec3& B) const;

  const TraceScene& scene_;
  mutable std::atomic<long> traced_{0};
};

/// Points placed on the non-emitting surfaces (both sides of two-sided ones): three quarters
/// stratified by area (tag "area"), an eighth within a short distance (log-uniform, 0.1 % to 3 %
/// of the scene's size) of the surfaces' own edges ("edge") and an eighth as near the lines
/// where other surfaces' edges lie on them ("contact": the foot of a wall or a block, where
/// errors concentrate; their share goes to edges in a scene without contacts). Points inside solids (every direction
/// ends on the back of a one-sided surface: the floor under a block) are not placed.
std::vector<SurfacePoint> placePoints(const TraceScene& scene, int count, uint64_t seed);

/// The surface side at a point the user gave (x, normal): the nearest surface within
/// `tolerance` (scene units) along the normal whose side faces it; the point is moved onto it.
/// False when there is none.
bool locatePoint(const TraceScene& scene, SurfacePoint& point, double tolerance);

}  // namespace rad::pathtrace
