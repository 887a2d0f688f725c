#pragma once
// What the progressive solver is asked for: when to stop, how hard to shoot, from how many
// points, and how much memory may keep form factors between shots.
#include <cstddef>

namespace rad {

/// Memory for keeping form factors between a patch's shots, MiB: a fixed budget (the Cornell
/// box at 4 000 elements needs about 40).
constexpr double kDefaultFactorCacheMb = 256;
/// Points an emitting patch shoots from, and at least this many on any other patch, raised near
/// other surfaces by k·(D/d)² (shooter_samples.h).
constexpr int kDefaultEmitterSamples = 64;
constexpr int kDefaultShooterSamples = 1;
constexpr double kDefaultProximitySamples = 0.7;
/// Coplanar patches far from other surfaces shoot together (shooter_clusters.h).
constexpr bool kDefaultClusterShooters = true;
/// A shot whose resolution follows its power draws no coarser hemicube than this.
constexpr int kLeastFollowingResolution = 64;

/// The defaults are the command line's (radiosity/settings.h resolves them), except ω: plain shooting here.
struct SolverOptions {
  double tolerance = 1e-3;   ///< stop when unshot/emitted power (luminance) falls below
  long maxShots = 0;         ///< 0: no limit
  double timeLimit = 0;      ///< seconds; 0: no limit
  double overshoot = 1;      ///< ω: shoot ω times the unshot power (1: plain shooting)
  int emitterSamples = kDefaultEmitterSamples;  ///< points on an emitting patch
  int shooterSamples = kDefaultShooterSamples;  ///< at least this many on any other patch (or cluster)
  /// More points on patches near other surfaces (sampleCount).
  double proximitySamples = kDefaultProximitySamples;
  /// Memory for keeping each sample's form factors after its first shot, so that a patch
  /// shooting again costs no hemicube (the factors are the same: same point, same rotation).
  /// A fixed budget, whatever the scene size; 0 recomputes every time.
  size_t factorCacheBytes = size_t(kDefaultFactorCacheMb * 1024 * 1024);
  /// Let coplanar patches shoot together where that takes fewer hemicubes than shooting them
  /// one by one (radiosity/shooting/shooter_clusters.h).
  bool clusters = kDefaultClusterShooters;
  /// The factor source's resolution R when shooting resolution follows the unshot power, else
  /// 0. A patch (or cluster) shooting with a share s of the strongest non-emitting shot's
  /// power so far draws R·∛s, snapped to R, R/√2 or R/2 and no coarser than
  /// kLeastFollowingResolution (followingResolution()); emitters keep their own. Only a
  /// shooter's first shot matters while its factors stay cached.
  int followingResolution = 0;
};

/// A shot's hemicube resolution for power share `share` (of the strongest non-emitting shot)
/// and finest resolution R: ∛share minimises Σ share/R under a budget of Σ R² pixels (a
/// hemicube's aliasing error ∝ 1/R, its cost ∝ R²), snapped in log to R, R/√2 or R/2, even.
int followingResolution(int R, double share);

}  // namespace rad
