#pragma once
// Effective settings: command-line flags override the scene's solver block, which overrides
// defaults relative to the scene size.
#include <optional>

#include "mesh/patch_mesh.h"
#include "mesh/scene.h"

namespace rad {

/// Default element edge: the scene diagonal divided by this.
constexpr double kDefaultElementsPerDiagonal = 25;
/// Default overshooting factor: on the Cornell box (docs/cornell_convergence.csv) ω = 1.3 reaches
/// 1 % error in 1 719 shots against 2 514 for plain shooting, and 0.1 % in 3 041 against 4 046.
constexpr double kDefaultOvershoot = 1.3;
/// Default memory for keeping form factors between a patch's shots, MiB: a fixed budget
/// (the Cornell box at 4 000 elements needs about 40).
constexpr double kDefaultFactorCacheMb = 256;
/// Default patch edge: this many element edges.
constexpr double kDefaultPatchToElement = 3;

struct Settings {
  double maxElementEdge = 0, maxPatchEdge = 0;
  int hemicubeResolution = 256;
  double tolerance = 1e-3;
  unsigned seed = 1;
  long maxShots = 0;         ///< 0: no limit
  double timeLimit = 0;      ///< seconds; 0: no limit
  double overshoot = kDefaultOvershoot;  ///< ω of overshooting; 1: plain shooting
  std::optional<double> exposure;  ///< unset: chosen automatically
  int emitterSamples = 64;   ///< at least this many shooting points on an emitting patch
  int shooterSamples = 4;    ///< on any other patch
  double factorCacheMb = kDefaultFactorCacheMb;  ///< memory for reusing form factors

  MeshSettings mesh() const { return {maxElementEdge, maxPatchEdge}; }
};

/// Merges `flags` over `scene.solver` over the defaults.
Settings resolveSettings(const Scene& scene, const SolverBlock& flags);

}  // namespace rad
