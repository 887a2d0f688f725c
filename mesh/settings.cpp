#include "mesh/settings.h"

namespace rad {

Settings resolveSettings(const Scene& scene, const SolverBlock& flags) {
  const SolverBlock& file = scene.solver;
  auto pick = [](const auto& flag, const auto& fromFile, auto fallback) {
    return flag ? *flag : fromFile ? *fromFile : fallback;
  };
  Settings s;
  s.maxElementEdge = pick(flags.maxElementEdge, file.maxElementEdge,
                          scene.diagonal() / kDefaultElementsPerDiagonal);
  s.maxPatchEdge = pick(flags.maxPatchEdge, file.maxPatchEdge,
                        s.maxElementEdge * kDefaultPatchToElement);
  s.cutContacts = pick(flags.cutContacts, file.cutContacts, true);
  s.adaptive = pick(flags.adaptive, file.adaptive, true);
  s.minElementEdge = pick(flags.minElementEdge, file.minElementEdge,
                          s.maxElementEdge / kDefaultMinElementRatio);
  s.contrast = pick(flags.contrast, file.contrast, kDefaultContrast);
  s.vertexDirect = pick(flags.vertexDirect, file.vertexDirect, true);
  s.emitterHemicubeResolution = pick(flags.emitterHemicubeResolution,
                                     file.emitterHemicubeResolution, kDefaultEmitterHemicubeResolution);
  s.hemicubeResolution =
      pick(flags.hemicubeResolution, file.hemicubeResolution, kDefaultHemicubeResolution);
  s.tolerance = pick(flags.tolerance, file.tolerance, 1e-3);
  s.seed = pick(flags.seed, file.seed, 1u);
  s.maxShots = pick(flags.maxShots, file.maxShots, 0L);
  s.timeLimit = pick(flags.timeLimit, file.timeLimit, 0.0);
  s.overshoot = pick(flags.overshoot, file.overshoot, kDefaultOvershoot);
  s.exposure = flags.exposure ? flags.exposure : file.exposure;
  s.emitterSamples = pick(flags.emitterSamples, file.emitterSamples, kDefaultEmitterSamples);
  s.shooterSamples = pick(flags.shooterSamples, file.shooterSamples, kDefaultShooterSamples);
  s.proximitySamples =
      pick(flags.proximitySamples, file.proximitySamples, kDefaultProximitySamples);
  s.factorCacheMb = pick(flags.factorCacheMb, file.factorCacheMb, kDefaultFactorCacheMb);
  return s;
}

}  // namespace rad
