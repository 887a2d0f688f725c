#include "radiosity/settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mesh/base/error.h"
#include "mesh/scene/geometry.h"

namespace rad {

double estimateElements(const Scene& scene, double edge) {
  double area = 0, polygons = 0;
  for (const auto& s : scene.surfaces) {
    for (const auto& p : s.polygons) area += polygonArea(p) * (s.twoSided ? 2 : 1);
    polygons += double(s.polygons.size()) * (s.twoSided ? 2 : 1);
  }
  // Every polygon (a mesh file's face) is at least one element, however small.
  return std::max(area / (std::sqrt(3.0) / 4 * edge * edge), polygons);
}

namespace {

/// The override, else the scene file's value, else the default.
template <class T, class U>
T pick(const std::optional<T>& flag, const std::optional<T>& file, U fallback) {
  return flag ? *flag : file ? *file : T(fallback);
}

/// Element and patch sizes, contacts and adaptive refinement.
void resolveMeshing(Settings& s, const Scene& scene, const SolverBlock& flags) {
  const SolverBlock& file = scene.solver;
  const MeshSettings mesh = resolveMeshSettings(scene, flags);
  s.quality = qualityOf(scene, flags);
  s.maxElementEdge = mesh.maxElementEdge;
  s.maxPatchEdge = mesh.maxPatchEdge;
  s.cutContacts = mesh.cutContacts;
  s.fixFacing = pick(flags.fixFacing, file.fixFacing, true);
  s.adaptive = pick(flags.adaptive, file.adaptive, true);
  s.finalGather = pick(flags.finalGather, file.finalGather, true);
  const double ratio = s.finalGather ? kGatherMinElementRatio : kDefaultMinElementRatio;
  s.minElementEdge = pick(flags.minElementEdge, file.minElementEdge, s.maxElementEdge / ratio);
  s.contrast = pick(flags.contrast, file.contrast, kDefaultContrast);
  s.vertexDirect = pick(flags.vertexDirect, file.vertexDirect, true);
  s.maxElements = pick(flags.maxElements, file.maxElements, kDefaultMaxElements);
}

/// The progressive solve's hemicubes, emitters' shooting points and tolerance: defaults as a
/// start for the final gather (`gatherStart`), or as the answer.
Shooting resolveShooting(bool gatherStart, const SolverBlock& file, const SolverBlock& flags) {
  Shooting s;
  s.emitterHemicubeResolution = pick(flags.emitterHemicubeResolution, file.emitterHemicubeResolution,
                                     gatherStart ? kGatherStartHemicubeResolution : kDefaultEmitterHemicubeResolution);
  s.hemicubeResolution = pick(flags.hemicubeResolution, file.hemicubeResolution,
                              gatherStart ? kGatherStartHemicubeResolution : kDefaultHemicubeResolution);
  s.emitterSamples = pick(flags.emitterSamples, file.emitterSamples,
                          gatherStart ? kGatherStartEmitterSamples : kDefaultEmitterSamples);
  s.tolerance = pick(flags.tolerance, file.tolerance, gatherStart ? kGatherStartTolerance : kDefaultTolerance);
  const bool stopGiven = flags.tolerance || file.tolerance || flags.maxShots || file.maxShots;
  s.shotsPerPatch = gatherStart && !stopGiven ? kGatherStartShotsPerPatch : 0;
  return s;
}

/// Hemicubes, shooting points and the factor cache.
void resolveShooting(Settings& s, const SolverBlock& file, const SolverBlock& flags) {
  static_cast<Shooting&>(s) = resolveShooting(false, file, flags);
  if (s.finalGather) s.gatherStart = resolveShooting(true, file, flags);
  const bool draft = s.quality == Quality::Draft, final = s.quality == Quality::Final;
  s.gatherResolution = pick(flags.gatherResolution, file.gatherResolution,
                            draft ? kDraftGatherResolution : kDefaultGatherResolution);
  s.gatherAccuracy = pick(flags.gatherAccuracy, file.gatherAccuracy,
                          draft ? kDraftGatherAccuracy : final ? 0.0 : kDefaultGatherAccuracy);
  s.seed = pick(flags.seed, file.seed, 1u);
  s.overshoot = pick(flags.overshoot, file.overshoot, kDefaultOvershoot);
  s.shooterSamples = pick(flags.shooterSamples, file.shooterSamples, kDefaultShooterSamples);
  s.proximitySamples = pick(flags.proximitySamples, file.proximitySamples, kDefaultProximitySamples);
  s.clusterShooters = pick(flags.clusterShooters, file.clusterShooters, kDefaultClusterShooters);
  s.resolutionFollowsPower = pick(flags.resolutionFollowsPower, file.resolutionFollowsPower, kDefaultResolutionFollowsPower);
  s.factorCacheMb = pick(flags.factorCacheMb, file.factorCacheMb, kDefaultFactorCacheMb);
}

/// When to stop, and the exposure shown.
void resolveStopping(Settings& s, const SolverBlock& file, const SolverBlock& flags) {
  s.maxShots = pick(flags.maxShots, file.maxShots, 0L);
  s.timeLimit = pick(flags.timeLimit, file.timeLimit, 0.0);
  s.exposure = flags.exposure ? flags.exposure : file.exposure;
}

/// Refuses before meshing what would not fit: a user who asks for 1e9 elements learns it now.
void checkElementCap(const Scene& scene, const Settings& s) {
  const double estimate = estimateElements(scene, s.maxElementEdge);
  if (estimate <= double(s.maxElements)) return;
  char found[160];
  std::snprintf(found, sizeof found, "%g (about %.3g elements)", s.maxElementEdge, estimate);
  throw SettingError(inputError(scene.path + ": solver.max_element_edge",
                                "an element edge giving at most " + std::to_string(s.maxElements) +
                                    " elements (raise the edge, or the cap solver.max_elements)",
                                found).what());
}

}  // namespace

Settings resolveSettings(const Scene& scene, const SolverBlock& flags) {
  Settings s;
  resolveMeshing(s, scene, flags);
  resolveShooting(s, scene.solver, flags);
  resolveStopping(s, scene.solver, flags);
  checkElementCap(scene, s);
  return s;
}

}  // namespace rad
