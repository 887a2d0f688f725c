#pragma once
// Shooter clusters: the patches of one plane grouped into a binary hierarchy, so that where
// they lie far from other surfaces, a group of them shoots its unshot power together from fewer
// points than its patches would one by one (each patch needs at least one hemicube). How many
// points a cluster needs (SampleCounter) keeps them no farther apart than 1/√2 of the distance
// from the cluster's nearest point to the nearest element facing it.
#include <vector>

#include <glm/vec3.hpp>

namespace rad {

class PatchMesh;

/// Patches of one surface side in one plane, near each other (not necessarily connected: a
/// partition standing on a floor may cross a floor's cluster, and then stands too near for it
/// to shoot).
struct ShooterCluster {
  std::vector<int> patches;   ///< at least two
  std::vector<int> elements;  ///< the patches' elements
  double area = 0;
  glm::dvec3 normal{0.0};
  glm::dvec3 origin{0.0};     ///< a point of the plane: the first patch's centroid
  /// An orthonormal frame of the plane (u, v, normal) and the cluster's extent in it: the
  /// rectangle [lo, hi] in (u, v) about `origin` holds every element corner.
  glm::dvec3 u{0.0}, v{0.0};
  double uLo = 0, uHi = 0, vLo = 0, vHi = 0;
  double diameter = 0;        ///< the rectangle's diagonal, at least the patches' span
  int parent = -1;            ///< the cluster holding this one, -1 at the top
};

/// Per plane (surface side, normal and offset equal to round-off), the non-emitting patches are
/// bisected recursively along the longest extent of their centroids, by count; every group of
/// two to `maxPatches` patches so made is a cluster.
class ShooterClusters {
 public:
  static constexpr int kDefaultMaxPatches = 16;

  explicit ShooterClusters(const PatchMesh& mesh, int maxPatches = kDefaultMaxPatches);

  int size() const { return int(clusters_.size()); }
  const ShooterCluster& operator[](int c) const { return clusters_[size_t(c)]; }
  /// The smallest cluster holding the patch, -1 if none (an emitter, alone in its plane).
  int above(int patch) const { return above_[size_t(patch)]; }

 private:
  /// Bisects `patches` (one plane's), recording each group of at most maxPatches; returns the
  /// group's cluster, or -1 when it is a single patch or too large.
  int bisect(std::vector<int> patches, int maxPatches);
  int record(std::vector<int> patches);

  const PatchMesh& mesh_;  // while building
  std::vector<ShooterCluster> clusters_;
  std::vector<int> above_;  // per patch
};

}  // namespace rad
