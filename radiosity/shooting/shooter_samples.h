#pragma once
// The points a patch shoots from: how many (SampleCounter) and where (patchSamples), each
// carrying its share of the patch's elements' power.
#include <mutex>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "radiosity/shooting/point_tree.h"
#include "radiosity/shooting/shooter_clusters.h"
#include "radiosity/shooting/solver_options.h"

namespace rad {

class PatchMesh;

/// A point a patch shoots from, carrying weights[k] of elements[k]'s unshot power.
struct ShooterSample {
  std::vector<int> elements;
  std::vector<double> weights;
  glm::dvec3 point{0.0}, normal{0.0};
};

/// A cluster's shooting points are spaced no wider than 1/√2 of the distance to the nearest
/// element facing it: k = 2 in k·(D/d)², where a patch has 0.7 (its own size keeps its points
/// closer). Measured on the Cornell box without the gather, a patch per 55 mm element (3 180
/// patches): no clusters 9 018 hemicubes and 2.755 % true error; with a cluster shooting
/// whenever it took at most half its patches' hemicubes, k = 16 / 4 / 2 / 1 / 0.7:
/// 9 009 / 8 236 / 6 912 / 6 567 / 6 406 hemicubes, 2.754 / 2.757 / 2.767 / 2.769 / 2.79 %.
constexpr double kClusterProximitySamples = 2;
/// A cluster counts no more points than this (it then shoots as patches).
constexpr int kMaxClusterPoints = 1 << 20;

/// How many points a patch shoots from: options.emitterSamples on an emitter; otherwise
/// options.shooterSamples, raised to proximitySamples·(D/d)² (at most emitterSamples), D the
/// patch's diameter and d the distance from its centroid to the nearest element of another
/// plane facing it: the proximity error of point shooters falls as the square of the points'
/// spacing (oracles.md §3). Element centroids sit in a bounding-volume hierarchy, so only nearby
/// ones are visited.
class SampleCounter {
 public:
  SampleCounter(const PatchMesh& mesh, const SolverOptions& options);
  int operator()(int patch) const;
  /// A cluster's points: k·(D/d)² with k = kClusterProximitySamples and d measured from the
  /// cluster's nearest point (not its centroid), at least the fewest, at most kMaxClusterPoints.
  int operator()(const ShooterCluster& cluster) const;

 private:
  /// The distance from the patch's centroid to the nearest element facing it, if under
  /// `reach` (HUGE_VAL otherwise).
  double nearestFacing(int patch, double reach) const;
  /// The distance from the cluster's nearest point to the nearest element facing it, if under
  /// `reach` (HUGE_VAL otherwise).
  double nearestFacing(const ShooterCluster& cluster, double reach) const;
  /// A patch's k·(D/d)² points, at least the fewest, at most the emitters' count.
  int proximityCount(double diameter, double nearest) const;

  /// The element centroids (none if no count needs them) and their normals, built on first
  /// use: a solve whose shots are all from emitters (the gather's start) needs none.
  const PointTree& centroids() const;
  const std::vector<glm::dvec3>& normals() const;

  const PatchMesh& mesh_;
  SolverOptions options_;
  mutable std::once_flag built_;
  mutable std::optional<PointTree> centroids_;
  mutable std::vector<glm::dvec3> normal_;  // per element, beside the centroids
};

/// `count` stratified samples over a patch. Each element is cut into m×m congruent triangles,
/// m chosen so that the patch has at least `count` parts spread by area; the parts are split
/// into `count` strata of about equal area by recursive bisection, and each stratum shoots its
/// parts' shares of their elements' power from its centroid. Each element's weights sum to 1.
std::vector<ShooterSample> patchSamples(const PatchMesh& mesh, int patch, int count);
/// The same over a cluster's elements.
std::vector<ShooterSample> clusterSamples(const PatchMesh& mesh, const ShooterCluster& cluster, int count);

}  // namespace rad
