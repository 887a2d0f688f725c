#pragma once
// Effective settings: command-line flags override the scene's solver block, which overrides
// defaults relative to the scene size.
#include <optional>

#include "mesh/base/error.h"
#include "mesh/mesh_settings.h"
#include "mesh/patch_mesh.h"
#include "mesh/scene/scene.h"
#include "radiosity/gather/final_gather.h"
#include "radiosity/shooting/solver_options.h"

namespace rad {

// The defaults, one line of why each; the measurements behind them are in docs/performance.md
// ("Why the defaults are what they are").

/// Overshooting ω: reaches 1 % on the Cornell box in a third fewer shots than plain shooting.
constexpr double kDefaultOvershoot = 1.3;
/// Hemicube resolution: with a point per patch, raised near other surfaces, within 2 % of a
/// fine solution on the Cornell box, faster than more points at 256.
constexpr int kDefaultHemicubeResolution = 128;
/// Emitters shoot at twice that: elements beside the blocks are under a pixel at 128.
constexpr int kDefaultEmitterHemicubeResolution = 256;
/// A patch first shooting with less unshot power than the strongest shot before it draws
/// coarser hemicubes, never coarser than kLeastFollowingResolution.
constexpr bool kDefaultResolutionFollowsPower = true;
/// With the final gather the progressive solve only starts the vertex system, which the gather
/// iterates to convergence from any start: a cheap start gives the same true error.
constexpr int kGatherStartHemicubeResolution = 64;
constexpr int kGatherStartEmitterSamples = 4;
constexpr double kGatherStartTolerance = 1e-2;
constexpr double kGatherStartShotsPerPatch = 0.1;
/// When the gather's rows fit its memory (it iterates), a hundredth of a shot per patch does,
/// and at most this many shots in all, however many patches.
constexpr double kIteratedStartShotsPerPatch = 0.01;
constexpr long kGatherStartMaxShots = 100;
/// Unshot power left when the progressive solve is the answer.
constexpr double kDefaultTolerance = 1e-3;
/// Adaptive refinement stops at the element edge over this; with the final gather refined
/// vertices cost rays, not hemicubes, so it goes deeper.
constexpr double kDefaultMinElementRatio = 4;
constexpr double kGatherMinElementRatio = 8;
/// Refinement threshold in display units (sRGB value in [0, 1]): about five of 255 levels.
constexpr double kDefaultContrast = 0.02;
/// A draft's gather: coarser hemicubes, and more vertices of a finely tessellated model taking
/// the light of gathering ones near them (a final solve gathers at every vertex).
constexpr int kDraftGatherResolution = 16;
constexpr double kDraftGatherAccuracy = 0.4;
/// Cap on elements: about 14 GiB at the ~7 KiB per element a solve takes, within 24 GiB.
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

/// The settings a solve runs by, resolved once (resolveSettings) and never rewritten. Its
/// Shooting is the progressive solve's as the answer; gatherStart is its shooting as the final
/// gather's start, and the gather's plan (radiosity/gather_plan.h) picks one.
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
  /// minElementEdge (a sharp change further, kSharpRefinement); the contact lines are then
  /// graded by that refinement, not beforehand.
  bool adaptive = true;
  double minElementEdge = 0;
  double contrast = kDefaultContrast;  ///< display units
  /// Show direct light computed at the vertices by rays (radiosity/light/direct_light.h).
  bool vertexDirect = true;
  /// Gather the light shown at every vertex through its own hemicube after the solve, the
  /// vertex system iterated to convergence (radiosity/gather/final_gather.h).
  bool finalGather = true;
  int gatherResolution = kDefaultGatherResolution;
  Quality quality = Quality::Default;  ///< what the defaults of the settings below were taken for
  /// Which vertices of the mesh before refinement gather (Ward's accuracy, GatherCache); 0: every one.
  double gatherAccuracy = kDefaultGatherAccuracy;
  /// With the final gather asked for: the progressive solve's shooting as its start (cheaper
  /// defaults, the values the user gave kept).
  std::optional<Shooting> gatherStart;
  /// Meshing is refused beyond this many elements (estimated before meshing), and adaptive
  /// refinement stops there.
  long maxElements = kDefaultMaxElements;

  /// What the progressive solve shoots with: as the gather's start (`gathered`, when the
  /// gather is asked for) or as the answer.
  const Shooting& shooting(bool gathered) const { return gathered && gatherStart ? *gatherStart : *this; }

  /// The mesher's settings; `refinementGrades`: whether adaptive refinement will follow and
  /// grade the contact lines (else the mesher grades them itself).
  MeshSettings mesh(bool refinementGrades = true) const {
    return {maxElementEdge, maxPatchEdge, cutContacts, contactGrading(adaptive && refinementGrades, finalGather)};
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
