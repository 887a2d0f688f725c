#include "radiosity/solve.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include <glm/common.hpp>

#include "mesh/base/color.h"
#include "mesh/base/error.h"
#include "mesh/base/parallel.h"
#include "mesh/results/default_camera.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/gather/gather_points.h"
#include "radiosity/result.h"

namespace rad {

namespace {

/// Passes the warnings from index `from` on to options.warn.
void passOn(const std::vector<std::string>& warnings, size_t from, const MeshingOptions& options) {
  if (!options.warn) return;
  for (size_t k = from; k < warnings.size(); ++k) options.warn(warnings[k]);
}

/// An emitter cut away entirely is an error before any ray is cast.
void requireEmitter(const MeshedScene& s) {
  for (int e = 0; e < s.mesh.elementCount(); ++e)
    if (luminance(s.mesh.emission(e)) > 0) return;
  throw inputError(s.scene.path + ": surfaces", "an emitting surface left after contacts are cut",
                   "every emitting surface enclosed by others and cut away");
}

int emittingPatches(const PatchMesh& mesh) {
  int emitting = 0;
  for (int p = 0; p < int(mesh.patches.size()); ++p) emitting += mesh.emits(p);
  return emitting;
}

/// The warning that refinement is off because the emitters are too many for rays.
std::string tooManyEmitters(int emitting) {
  return "adaptive subdivision off: " + std::to_string(emitting) + " emitting patches, more than the " +
         std::to_string(kMaxRayEmitterPatches) + " rays are cast to; the hemicubes' direct light is shown";
}

/// Whether rays, and the refinement that grades the contact lines, are sure to follow: decided
/// before meshing, so that the mesh is built once. Else the mesher grades them itself (which
/// changes the mesh only without the final gather: contactGrading).
bool refinementWillGrade(const Scene& scene, const Settings& settings) {
  return settings.adaptive && mostEmittingPatches(scene, settings.maxElementEdge) <= kMaxRayEmitterPatches;
}

/// Whether the vertices get direct light by rays: they are asked for (or refinement needs
/// them), and the mesh's emitting patches are at least one and at most kMaxRayEmitterPatches
/// (DirectLight::enabled); too many, adaptive refinement is left out, with a warning.
bool castRays(MeshedScene& s) {
  if (!s.settings.vertexDirect && !s.settings.adaptive) return false;
  const int emitting = emittingPatches(s.mesh);
  if (s.settings.adaptive && emitting > kMaxRayEmitterPatches) s.mesh.warnings.push_back(tooManyEmitters(emitting));
  return emitting > 0 && emitting <= kMaxRayEmitterPatches;
}

AdaptiveOptions adaptiveOptions(const Settings& settings) {
  AdaptiveOptions options;
  options.minElementEdge = settings.minElementEdge;
  options.maxElements = settings.maxElements;
  options.contrast = settings.contrast;
  options.exposure = settings.exposure.value_or(0.0);
  // Gaps narrower than the smallest element: only gathered light shows what falls off there.
  if (settings.finalGather) options.gapReach = settings.minElementEdge;
  return options;
}

/// Refines the mesh where the direct light changes visibly, keeping the mesh as it was
/// (`unrefined`, a copy: MeshedScene::base) when anything was refined.
void refine(MeshedScene& s, std::shared_ptr<const PatchMesh> unrefined) {
  s.adaptive = refineAdaptively(s.mesh, *s.direct, adaptiveOptions(s.settings));
  if (s.adaptive.elementsAfter > s.adaptive.elementsBefore) s.base = std::move(unrefined);
}

/// What the scene's time limit leaves after meshing so far (0: no limit).
double timeLeftAfter(const Settings& settings, std::chrono::steady_clock::time_point started) {
  if (!(settings.timeLimit > 0)) return 0;
  const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return std::max(kNoTimeLeft, settings.timeLimit - spent);
}

/// The gather's hemicubes over the mesh as built (before refinement, which they do not draw;
/// `unrefined`: a copy of it, or null), started on threads of their own if a solve follows
/// and the gather, as it looks now, will run and iterate. The plan made after the rays keeps
/// them only if it runs.
std::shared_ptr<GatherAhead> startGatherAhead(const MeshedScene& s, const GatherEstimate& estimate,
                                              std::shared_ptr<const PatchMesh> unrefined,
                                              const MeshingOptions& meshing) {
  const GatherOptions options = gatherOptions(s.settings, s.started);
  if (!meshing.gatherAhead || !s.settings.finalGather || !estimate.iterates(options)) return nullptr;
  if (!gatherLeftOut(estimate, workerCount(0), timeLeft(s), s.settings.timeLimit).empty()) return nullptr;
  if (!unrefined) unrefined = std::make_shared<const PatchMesh>(s.mesh);
  return std::make_shared<GatherAhead>(std::move(unrefined), s.scene.diagonal(), options);
}

/// The direct light at the vertices by rays and, with it, adaptive refinement (`unrefined`: a
/// copy of the mesh, or null without refinement).
void lightAndRefine(MeshedScene& s, std::shared_ptr<const PatchMesh> unrefined) {
  s.direct = std::make_unique<DirectLight>(s.mesh, s.scene.diagonal());
  RAD_CHECK(s.direct->enabled());
  if (s.settings.adaptive)
    refine(s, std::move(unrefined));
  else
    s.direct->update(s.mesh);
  if (s.base && s.settings.finalGather) s.ownHemicube = nearSurfaces(s.mesh, *s.base, *s.direct);
  if (!s.settings.vertexDirect) s.direct.reset();
}

/// The direct light at the vertices by rays (castRays) and, with it, adaptive refinement; then
/// the final gather's plan, its cost estimated over the mesh before refinement (its hemicubes
/// rendering meanwhile) and its budget checked with the time the rays left.
void lightVertices(MeshedScene& s, const MeshingOptions& options) {
  s.adaptive.elementsBefore = s.adaptive.elementsAfter = s.mesh.elementCount();
  const bool rays = castRays(s);
  std::shared_ptr<const PatchMesh> unrefined;
  if (rays && s.settings.adaptive) unrefined = std::make_shared<const PatchMesh>(s.mesh);
  GatherEstimate estimate{};
  if (s.settings.finalGather) estimate = estimateGather(s.mesh, s.scene.diagonal(), gatherOptions(s.settings, s.started));
  std::shared_ptr<GatherAhead> ahead = startGatherAhead(s, estimate, unrefined, options);
  if (rays) lightAndRefine(s, std::move(unrefined));
  if (const long own = ownHemicubes(s); own > 0) estimate = estimate.forVertices(estimate.vertices + double(own));
  s.gather = planGather(s.settings, estimate, s.mesh.patches.size(), timeLeft(s), std::move(ahead));
  if (!s.gather.leftOut.empty()) s.mesh.warnings.push_back(s.gather.leftOut);
}

/// The solver options of the scene's settings, the time limit what meshing left of it.
SolverOptions limitedOptions(const MeshedScene& s) {
  SolverOptions options = solverOptions(s);
  options.timeLimit = timeLeft(s);
  return options;
}

/// Sets every negative channel to 0; the number of elements that had one.
int clampNegative(std::vector<glm::dvec3>& B) {
  int clamped = 0;
  for (auto& x : B)
    if (x.x < 0 || x.y < 0 || x.z < 0) {
      ++clamped;
      x = glm::max(x, glm::dvec3(0.0));
    }
  return clamped;
}

}  // namespace

Scene loadSceneToSolve(const std::string& path) {
  Scene scene = loadScene(path);
  if (!scene.hasEmitter())
    throw inputError(scene.path + ": surfaces", "at least one surface whose material has an emission",
                     "none (radiosity light comes from emitting surfaces)");
  return scene;
}

MeshedScene meshScene(Scene scene, const Settings& settings, const MeshingOptions& options) {
  MeshedScene s{std::move(scene), settings, {}, nullptr, {}, nullptr, {}, std::chrono::steady_clock::now(), {}, {}};
  const auto facingStart = StageTimes::Clock::now();
  if (settings.fixFacing) s.facing = turnToLitSpace(s.scene);
  const double facingSeconds = StageTimes::since(facingStart);
  s.mesh = buildPatchMesh(s.scene, s.settings.mesh(refinementWillGrade(s.scene, settings)));
  s.mesh.stats.stages.add("facing", facingSeconds);
  s.mesh.warnings.insert(s.mesh.warnings.begin(), s.facing.warnings.begin(), s.facing.warnings.end());
  passOn(s.mesh.warnings, 0, options);
  if (options.requireEmitter) requireEmitter(s);
  const size_t passed = s.mesh.warnings.size();
  lightVertices(s, options);
  passOn(s.mesh.warnings, passed, options);
  return s;
}

double timeLeft(const MeshedScene& scene) { return timeLeftAfter(scene.settings, scene.started); }

SolverOptions solverOptions(const Settings& settings, const Shooting& shooting, size_t patches) {
  SolverOptions options;
  options.tolerance = shooting.tolerance;
  options.maxShots = settings.maxShots;
  if (!options.maxShots && shooting.shotsPerPatch > 0)
    options.maxShots = std::max(1L, long(std::ceil(shooting.shotsPerPatch * double(patches))));
  options.timeLimit = settings.timeLimit;
  options.overshoot = settings.overshoot;
  options.emitterSamples = shooting.emitterSamples;
  options.shooterSamples = settings.shooterSamples;
  options.proximitySamples = settings.proximitySamples;
  options.clusters = settings.clusterShooters;
  options.followingResolution = settings.resolutionFollowsPower ? shooting.hemicubeResolution : 0;
  options.factorCacheBytes = size_t(settings.factorCacheMb * 1024 * 1024);
  return options;
}

SolverOptions solverOptions(const MeshedScene& scene) {
  return solverOptions(scene.settings, scene.gather.shooting, scene.mesh.patches.size());
}

std::unique_ptr<HemicubeFactors> hemicubeFactors(const MeshedScene& s, int workers) {
  // With the gather on, the shots are only its start: their hemicubes draw flat regions too.
  const Shooting& shooting = s.gather.shooting;
  return std::make_unique<HemicubeFactors>(s.mesh, shooting.hemicubeResolution, s.scene.diagonal(), s.settings.seed,
                                           workers, shooting.emitterHemicubeResolution, s.gather.on);
}

RadiositySolve::RadiositySolve(const MeshedScene& scene, int workers)
    : RadiositySolve(scene, limitedOptions(scene), workers) {}

RadiositySolve::RadiositySolve(const MeshedScene& scene, const SolverOptions& options, int workers)
    : scene_(scene), workers_(workers), factors_(hemicubeFactors(scene, workers)),
      solver_(scene.mesh, *factors_, options) {}

// Overshooting can leave a slightly negative channel mid-solve; a result never carries one.
// With direct light from rays at the vertices, the emission not yet shot is already shown,
// so the ambient term leaves it out.
Solution RadiositySolve::bake(bool gather) const {
  Solution b;
  b.converged = solver_.stopReason() == ProgressiveSolver::Stop::Tolerance;
  const bool raysShowEmission = bool(scene_.direct);
  b.ambient = b.converged ? glm::dvec3(0.0) : glm::max(solver_.ambient(raysShowEmission), glm::dvec3(0.0));
  b.B = solver_.radiosity();
  b.clamped = clampNegative(b.B);
  if (scene_.direct) b.direct = VertexDirect{solver_.direct(), scene_.direct->radiosity(), scene_.base.get()};
  if (gather && scene_.gather.on) gatherAtVertices(b);
  return b;
}

void RadiositySolve::gatherAtVertices(Solution& b) const {
  const PatchMesh& mesh = scene_.mesh;
  std::vector<glm::dvec3> start = shownAtVertices(scene_, b);
  const std::vector<glm::dvec3> emission = vertexEmission(mesh);
  for (size_t v = 0; v < start.size(); ++v) start[v] = glm::max(start[v] - emission[v], glm::dvec3(0.0));
  GatherOptions options = gatherOptions(scene_.settings, scene_.started);
  options.workers = workers_;
  const std::vector<glm::dvec3>* direct = b.direct ? &b.direct->vertex : nullptr;
  const GatherRows* rendered = scene_.gather.ahead ? &scene_.gather.ahead->rows() : nullptr;
  std::vector<glm::dvec3> gathered =
      finalGather(mesh, scene_.base.get(), scene_.scene.diagonal(), start, direct, options, &b.gather, rendered,
                  &scene_.ownHemicube);
  if (b.gather.timedOut) return;  // the progressive solution stays, with its ambient term
  b.gathered = std::move(gathered);
  b.B = elementMeans(mesh, *b.gathered);
  b.ambient = glm::dvec3(0.0);
}

Solution solveRadiosity(const MeshedScene& scene) {
  RadiositySolve solve(scene);
  while (solve.step()) {
  }
  return solve.bake();
}

std::vector<glm::dvec3> shownAtVertices(const MeshedScene& scene, const Solution& solution) {
  if (solution.gathered) return *solution.gathered;
  return shownVertexRadiosity(scene.mesh, solution.B, solution.ambient,
                              solution.direct ? &*solution.direct : nullptr);
}

double exposureOf(const MeshedScene& scene, const Solution& solution) {
  return scene.settings.exposure ? *scene.settings.exposure : autoExposure(scene.mesh, solution.B);
}

Camera cameraOf(const Scene& scene) { return scene.camera ? *scene.camera : defaultCamera(scene); }

void writeSolution(const std::string& path, const MeshedScene& scene, const Solution& solution) {
  if (solution.gathered)
    return writeVertexResult(path, scene.mesh, *solution.gathered, solution.B, exposureOf(scene, solution),
                             cameraOf(scene.scene));
  writeResult(path, scene.mesh, solution.B, solution.ambient, exposureOf(scene, solution),
              cameraOf(scene.scene), solution.direct ? &*solution.direct : nullptr);
}

}  // namespace rad
