#pragma once
// Effective settings: command-line flags override the scene's solver block, which overrides
// defaults relative to the scene size.
#include <optional>

#include "mesh/patch_mesh.h"
#include "mesh/scene.h"

namespace rad {

/// Default element edge: the scene diagonal divided by this.
constexpr double kDefaultElementsPerDiagonal = 25;
/// Default patch edge: this many element edges.
constexpr double kDefaultPatchToElement = 3;

struct Settings {
  double maxElementEdge = 0, maxPatchEdge = 0;
  int hemicubeResolution = 256;
  double tolerance = 1e-3;
  unsigned seed = 1;
  long maxShots = 0;         ///< 0: no limit
  double timeLimit = 0;      ///< seconds; 0: no limit
  double overshoot = 1;      ///< ω of overshooting; 1: plain shooting
  std::optional<double> exposure;  ///< unset: chosen automatically
  int emitterSamples = 64;   ///< at least this many shooting points on an emitting patch
  int shooterSamples = 4;    ///< on any other patch

  MeshSettings mesh() const { return {maxElementEdge, maxPatchEdge}; }
};

/// Merges `flags` over `scene.solver` over the defaults.
Settings resolveSettings(const Scene& scene, const SolverBlock& flags);

}  // namespace rad
