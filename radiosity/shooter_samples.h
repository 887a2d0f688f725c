#pragma once
// The points a patch shoots from: how many (SampleCounter) and where (patchSamples), each
// carrying its share of the patch's elements' power.
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/spatial_hash.h"
#include "radiosity/solver_options.h"

namespace rad {

class PatchMesh;

/// A point a patch shoots from, carrying weights[k] of elements[k]'s unshot power.
struct ShooterSample {
  std::vector<int> elements;
  std::vector<double> weights;
  glm::dvec3 point{0.0}, normal{0.0};
};

/// How many points a patch shoots from: options.emitterSamples on an emitter; otherwise
/// options.shooterSamples, raised to proximitySamples·(D/d)² (at most emitterSamples), D the
/// patch's diameter and d the distance from its centroid to the nearest element of another
/// plane facing it: the proximity error of point shooters falls as the square of the points'
/// spacing (oracles.md §3). Element centroids sit in a spatial hash, so only nearby ones are
/// visited.
class SampleCounter {
 public:
  SampleCounter(const PatchMesh& mesh, const SolverOptions& options);
  int operator()(int patch) const;

 private:
  /// The distance from the patch's centroid to the nearest element facing it within `reach`
  /// (perhaps a little beyond; HUGE_VAL when there is none).
  double nearestFacing(int patch, double reach) const;

  const PatchMesh& mesh_;
  SolverOptions options_;
  SpatialHash centroids_;  // element centroids, in cells of the mean patch diameter
};

/// `count` stratified samples over a patch. Each element is cut into m×m congruent triangles,
/// m chosen so that the patch has at least `count` parts spread by area; the parts are split
/// into `count` strata of about equal area by recursive bisection, and each stratum shoots its
/// parts' shares of their elements' power from its centroid. Each element's weights sum to 1.
std::vector<ShooterSample> patchSamples(const PatchMesh& mesh, int patch, int count);

}  // namespace rad
