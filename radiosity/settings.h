#pragma once
// Effective settings: command-line flags override the scene's solver block, which overrides
// defaults relative to the scene size.
#include <optional>

#include "mesh/error.h"
#include "mesh/mesh_settings.h"
#include "mesh/patch_mesh.h"
#include "mesh/scene.h"
#include "radiosity/final_gather.h"

namespace rad {

/// Default overshooting factor: on the Cornell box (docs/cornell_convergence.csv) ω = 1.3 reaches
/// 1 % error in 1 719 shots against 2 514 for plain shooting, and 0.1 % in 3 041 against 4 046.
constexpr double kDefaultOvershoot = 1.3;
/// Default memory for keeping form factors between a patch's shots, MiB: a fixed budget
/// (the Cornell box at 4 000 elements needs about 40).
constexpr double kDefaultFactorCacheMb = 256;
/// Default hemicube resolution and shooting points. Measured on the Cornell box at 3 958
/// elements against a fine solution (element-sized patches, 16 points each, R = 512): R = 128
/// with 1 point per patch raised to 0.7·(D/d)² near other surfaces is within 2.0 % (L2) in
/// 0.41 s; R = 256 with 4 points on every patch was within 2.8 % in 0.58 s.
constexpr int kDefaultHemicubeResolution = 128;
/// Emitters shoot at twice that: measured on the Cornell box's floor 4 mm from the blocks,
/// the direct light's worst error over three seeds is 3.5–7.5 % at 128, 1.9–2.8 % at 256
/// (elements there are 6 mm, under one pixel at 128), for 128 hemicubes of about 1 200.
constexpr int kDefaultEmitterHemicubeResolution = 256;
constexpr int kDefaultShooterSamples = 1;
constexpr int kDefaultEmitterSamples = 64;
constexpr double kDefaultProximitySamples = 0.7;
/// Coplanar patches far from other surfaces shoot together (radiosity/shooter_clusters.h).
constexpr bool kDefaultClusterShooters = true;
/// A patch first shooting with less unshot power than the strongest shot before it draws
/// coarser hemicubes, never coarser than this (radiosity/solver_options.h).
constexpr bool kDefaultResolutionFollowsPower = true;
constexpr int kLeastFollowingResolution = 64;
/// With the final gather the progressive solve only starts the vertex system, which the gather
/// iterates to convergence from any start: its shooting defaults are then a cheap start. On
/// the Cornell box the gathered true error is the same to 0.01 % (1.70 %, 4.04 % within 50 mm
/// of the blocks) from 4 points per emitting patch, every hemicube at 64 and 1 % unshot as from
/// the defaults above, and the solve takes 0.15 s instead of 0.55 s.
/// It also stops once the patches have shot this many times each on average: the gather needs
/// no more (the Cornell box's gathered true error is the same to 0.01 % from 20 shots as from
/// 726, one iteration more; a stiff scene, ρ = 0.99, needs 195 000 shots to reach 1 % and the
/// gather converges from 1 shot in 6 iterations).
constexpr int kGatherStartHemicubeResolution = 64;
constexpr int kGatherStartEmitterSamples = 4;
constexpr double kGatherStartTolerance = 1e-2;
constexpr double kGatherStartShotsPerPatch = 0.1;
/// When the gather's rows fit its memory, the vertex system is iterated to its own solution
/// from any start, and a hundredth of a shot per patch does (CornellBox-Original 4 shots
/// instead of 38, the Cornell box 2, the doorway 3, the ρ = 0.99 closed box 1: the same
/// iterations, the doorway one more, and the same true errors), at most this many in all: a
/// tenth of a shot per patch grows with the scene (Modern Hall split to 100k triangles, a patch
/// per face: 10 000 shots, minutes), while the iteration only takes a few more steps from a
/// rougher start.
constexpr double kIteratedStartShotsPerPatch = 0.01;
constexpr long kGatherStartMaxShots = 100;
constexpr double kDefaultTolerance = 1e-3;

/// Default minimum element edge of adaptive refinement: the element edge divided by this.
/// With the final gather, refined vertices cost rays, not hemicubes (radiosity/gather_points.h),
/// so refinement goes deeper: on the Cornell box within 50 mm of the blocks (shadow edges
/// meeting the blocks' feet) 4.04 % at 4, 3.83 % at 8, for 0.71 s and 1.03 s. Without it every
/// refined element is drawn by every shooter's hemicube (0.87 s at 4, 1.31 s at 8).
constexpr double kDefaultMinElementRatio = 4;
constexpr double kGatherMinElementRatio = 8;
/// Default contrast threshold of adaptive refinement, in display units (the sRGB-encoded
/// value in [0, 1] of the exposed radiosity): about five of 255 display levels.
constexpr double kDefaultContrast = 0.02;
/// Default cap on elements (meshing and refinement): about 14 GiB at the ~7 KiB per element a
/// solve takes (45 000 elements: 328 MiB peak), within this 24 GiB machine class.
constexpr long kDefaultMaxElements = 2'000'000;

/// A setting whose value cannot be used, from the scene's solver block or an override: the
/// message names it as in the scene file (solver.max_element_edge); a command line maps that
/// to its flag.
class SettingError : public InputError {
 public:
  using InputError::InputError;
};

/// What the progressive solve shoots with, and when it stops.
struct Shooting {
  int hemicubeResolution = kDefaultHemicubeResolution;
  int emitterHemicubeResolution = kDefaultEmitterHemicubeResolution;
  int emitterSamples = kDefaultEmitterSamples;  ///< shooting points on an emitting patch
  double tolerance = kDefaultTolerance;
  /// Stop after this many shots per patch, unless maxShots is set (0: no such stop).
  double shotsPerPatch = 0;
};

struct Settings : Shooting {
  double maxElementEdge = 0, maxPatchEdge = 0;
  unsigned seed = 1;
  long maxShots = 0;         ///< 0: no limit
  double timeLimit = 0;      ///< seconds; 0: no limit
  double overshoot = kDefaultOvershoot;  ///< ω of overshooting; 1: plain shooting
  std::optional<double> exposure;  ///< unset: chosen automatically
  int shooterSamples = kDefaultShooterSamples;  ///< at least this many on any other patch (or cluster)
  double proximitySamples = kDefaultProximitySamples;  ///< k of k·(D/d)² points near surfaces
  double factorCacheMb = kDefaultFactorCacheMb;  ///< memory for reusing form factors
  bool clusterShooters = kDefaultClusterShooters;  ///< coplanar patches may shoot together
  bool resolutionFollowsPower = kDefaultResolutionFollowsPower;  ///< dimmer shots, coarser hemicubes

  bool cutContacts = true;   ///< cut surfaces along contacts, leave out what they enclose
  /// Turn mesh-file surfaces that the lit space sees from their backs round (mesh/facing.h).
  bool fixFacing = true;
  /// Refine where the direct light changes visibly (radiosity/adaptive.h), down to
  /// minElementEdge; the contact lines are then graded by that refinement, not beforehand.
  bool adaptive = true;
  double minElementEdge = 0;
  double contrast = kDefaultContrast;  ///< display units
  /// Show direct light computed at the vertices by rays (radiosity/direct_light.h).
  bool vertexDirect = true;
  /// Gather the light shown at every vertex through its own hemicube after the solve, the
  /// vertex system iterated to convergence (radiosity/final_gather.h).
  bool finalGather = true;
  int gatherResolution = kDefaultGatherResolution;
  /// With the final gather: the shooting to use instead when it is skipped (Shooting's
  /// defaults then the full ones, not the gather's start).
  std::optional<Shooting> ungathered;
  /// Meshing is refused beyond this many elements (estimated before meshing), and adaptive
  /// refinement stops there.
  long maxElements = kDefaultMaxElements;

  MeshSettings mesh() const {
    return {maxElementEdge, maxPatchEdge, cutContacts, contactGrading(adaptive, finalGather)};
  }
};

/// Merges `flags` over `scene.solver` over the defaults. Throws InputError when the element
/// edge would need more than maxElements elements (estimated from the scene's area).
Settings resolveSettings(const Scene& scene, const SolverBlock& flags);

/// Elements a uniform mesh of the scene with edges of at most `edge` has, about: its area
/// (both sides of two-sided surfaces) over the area of an equilateral triangle of that edge,
/// and at least one per polygon (a mesh file's face).
double estimateElements(const Scene& scene, double edge);

}  // namespace rad
