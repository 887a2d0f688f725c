#include "radiosity/solve.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include <glm/common.hpp>

#include "mesh/color.h"
#include "mesh/default_camera.h"
#include "mesh/error.h"
#include "mesh/parallel.h"
#include "radiosity/result.h"

namespace rad {

namespace {

/// Passes the warnings from index `from` on to options.warn.
void passOn(const std::vector<std::string>& warnings, size_t from, const MeshingOptions& options) {
  if (!options.warn) return;
  for (size_t k = from; k < warnings.size(); ++k) options.warn(warnings[k]);
}

/// The gather's options by the scene's settings, its deadline what the time limit sets.
GatherOptions gatherOptions(const MeshedScene& s) {
  GatherOptions options;
  options.resolution = s.settings.gatherResolution;
  options.seed = s.settings.seed;
  if (s.settings.timeLimit > 0)
    options.deadline = s.started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                       std::chrono::duration<double>(s.settings.timeLimit));
  return options;
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

/// Without rays there is no refinement to grade the contact lines: they are graded by the
/// mesher instead, as with adaptive refinement off (the mesh is built again if that differs).
void meshWithoutRays(MeshedScene& s) {
  const int emitting = emittingPatches(s.mesh);
  if (!s.settings.adaptive || emitting <= kMaxRayEmitterPatches) return;
  Settings graded = s.settings;
  graded.adaptive = false;
  if (graded.mesh().contactGrading != s.settings.mesh().contactGrading) {
    s.mesh = buildPatchMesh(s.scene, graded.mesh());
    // The same repairs first, as meshScene put them: only what follows is new.
    s.mesh.warnings.insert(s.mesh.warnings.begin(), s.facing.warnings.begin(), s.facing.warnings.end());
  }
  s.adaptive.elementsBefore = s.adaptive.elementsAfter = s.mesh.elementCount();
  s.mesh.warnings.push_back(tooManyEmitters(emitting));
}

AdaptiveOptions adaptiveOptions(const Settings& settings) {
  AdaptiveOptions options;
  options.minElementEdge = settings.minElementEdge;
  options.maxElements = settings.maxElements;
  options.contrast = settings.contrast;
  options.exposure = settings.exposure.value_or(0.0);
  return options;
}

/// Refines the mesh where the direct light changes visibly, keeping the mesh as it was
/// (`unrefined`, a copy: MeshedScene::base) when anything was refined.
void refine(MeshedScene& s, std::shared_ptr<const PatchMesh> unrefined) {
  s.adaptive = refineAdaptively(s.mesh, *s.direct, adaptiveOptions(s.settings));
  if (s.adaptive.elementsAfter > s.adaptive.elementsBefore) s.base = std::move(unrefined);
}

void decideGather(MeshedScene& s, std::shared_ptr<const PatchMesh> unrefined, const MeshingOptions& meshing);

/// The gather left out (`why`, in a warning): the progressive solve shoots as it would
/// without it.
void skipGather(MeshedScene& s, const std::string& why) {
  if (s.settings.ungathered) static_cast<Shooting&>(s.settings) = *s.settings.ungathered;
  s.mesh.warnings.push_back(why);
}

/// The direct light at the vertices by rays and, with it, adaptive refinement; or, when the
/// emitters are too many for rays, the mesh the hemicubes alone need. The final gather is
/// decided once the mesh it draws is known: before refinement, which it does not draw.
void lightVertices(MeshedScene& s, const MeshingOptions& options) {
  s.adaptive.elementsBefore = s.adaptive.elementsAfter = s.mesh.elementCount();
  if (!s.settings.vertexDirect && !s.settings.adaptive) return decideGather(s, nullptr, options);
  if (const int emitting = emittingPatches(s.mesh); emitting == 0 || emitting > kMaxRayEmitterPatches) {
    // No rays (as DirectLight::enabled says).
    meshWithoutRays(s);
    return decideGather(s, nullptr, options);
  }
  // The gather first: its hemicubes render while the rays' scene is built and they are cast.
  std::shared_ptr<const PatchMesh> unrefined;
  if (s.settings.adaptive) unrefined = std::make_shared<const PatchMesh>(s.mesh);
  decideGather(s, unrefined, options);
  s.direct = std::make_unique<DirectLight>(s.mesh, s.scene.diagonal());
  RAD_CHECK(s.direct->enabled());
  if (s.settings.adaptive)
    refine(s, std::move(unrefined));
  else
    s.direct->update(s.mesh);
  if (!s.settings.vertexDirect) s.direct.reset();
}

/// What timeLeft says once the time limit is spent (positive: 0 would mean no limit).
constexpr double kNoTimeLeft = 1e-9;
/// The gather may take at most this share of the time a time limit leaves after meshing.
constexpr double kGatherShareOfTimeLeft = 0.5;

/// The final gather if the settings ask for it and it fits the budget (gatherLeftOut).
/// Skipped, the progressive solve is the answer and shoots as it would without the gather.
/// Gathered and iterated, its hemicubes over the mesh as it is now (before refinement, which
/// they do not draw; `unrefined`: a copy of it, or null) start rendering at once if
/// meshing.gatherAhead says a solve follows.
void decideGather(MeshedScene& s, std::shared_ptr<const PatchMesh> unrefined, const MeshingOptions& meshing) {
  if (!s.settings.finalGather) return;
  const GatherOptions options = gatherOptions(s);
  const GatherEstimate estimate = s.gatherEstimate = estimateGather(s.mesh, s.scene.diagonal(), options);
  const std::string leftOut = gatherLeftOut(estimate, workerCount(0), timeLeft(s), s.settings.timeLimit);
  s.gather = leftOut.empty();
  if (!s.gather) return skipGather(s, leftOut);
  if (!estimate.iterates(options)) return;
  // Iterated to its own solution, the gather needs only a start: a hundredth of a shot per
  // patch, no more than kGatherStartMaxShots shots however many patches there are. Under a
  // time limit the start may be what is shown (the gather given up at its deadline): it keeps
  // its tenth of a shot per patch then.
  const double patches = double(s.mesh.patches.size());
  if (s.settings.shotsPerPatch > 0) {
    const double perPatch = s.settings.timeLimit > 0 ? s.settings.shotsPerPatch
                                                     : std::min(s.settings.shotsPerPatch, kIteratedStartShotsPerPatch);
    s.settings.shotsPerPatch = std::min(perPatch, double(kGatherStartMaxShots) / patches);
  }
  if (!meshing.gatherAhead) return;
  if (!unrefined) unrefined = std::make_shared<const PatchMesh>(s.mesh);
  s.gatherAhead = std::make_shared<GatherAhead>(std::move(unrefined), s.scene.diagonal(), options);
}

/// Under a time limit, the gather decided before the rays is decided again with the time they
/// left (its hemicubes, if rendering, are stopped).
void recheckGather(MeshedScene& s) {
  if (!s.gather || !(s.settings.timeLimit > 0)) return;
  const std::string leftOut = gatherLeftOut(s.gatherEstimate, workerCount(0), timeLeft(s), s.settings.timeLimit);
  if (leftOut.empty()) return;
  s.gather = false;
  s.gatherAhead.reset();
  skipGather(s, leftOut);
}

/// The solver options of the scene's settings, the time limit what meshing left of it.
SolverOptions limitedOptions(const MeshedScene& s) {
  SolverOptions options = solverOptions(s.settings, s.mesh.patches.size());
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

std::string gatherLeftOut(const GatherEstimate& estimate, int workers, double timeLeft, double timeLimit) {
  const double seconds = estimate.seconds(workers), oneCore = estimate.seconds(1);
  char text[320];
  if (timeLeft > 0 && timeLeft <= kNoTimeLeft)
    std::snprintf(text, sizeof text,
                  "final gather skipped, and no shot: meshing took all of the %.3g s time limit; the direct light "
                  "and the ambient term are shown",
                  timeLimit);
  else if (oneCore > kMaxGatherSeconds)
    std::snprintf(text, sizeof text,
                  "final gather skipped: its hemicubes would take about %.2g s on one core, more than the %.0f s "
                  "it may (a quarter of an hour on two); the progressive solution is shown at the vertices (coarser "
                  "elements gather: raise solver.max_element_edge)",
                  oneCore, kMaxGatherSeconds);
  else if (timeLeft > 0 && seconds > kGatherShareOfTimeLeft * timeLeft)
    std::snprintf(text, sizeof text,
                  "final gather skipped: it would take about %.2g s of the %.2g s the time limit leaves after "
                  "meshing; the progressive solution is shown at the vertices, shot until the time limit",
                  seconds, timeLeft);
  else
    return {};
  return text;
}

Scene loadSceneToSolve(const std::string& path) {
  Scene scene = loadScene(path);
  if (!scene.hasEmitter())
    throw inputError(scene.path + ": surfaces", "at least one surface whose material has an emission",
                     "none (radiosity light comes from emitting surfaces)");
  return scene;
}

MeshedScene meshScene(Scene scene, const Settings& settings, const MeshingOptions& options) {
  MeshedScene s{std::move(scene), settings, {}, nullptr, {}, nullptr, false, {}, {}, std::chrono::steady_clock::now(), {}};
  const auto facingStart = StageTimes::Clock::now();
  if (settings.fixFacing) s.facing = turnToLitSpace(s.scene);
  const double facingSeconds = StageTimes::since(facingStart);
  s.mesh = buildPatchMesh(s.scene, s.settings.mesh());
  s.mesh.stats.stages.add("facing", facingSeconds);
  s.mesh.warnings.insert(s.mesh.warnings.begin(), s.facing.warnings.begin(), s.facing.warnings.end());
  passOn(s.mesh.warnings, 0, options);
  if (options.requireEmitter) requireEmitter(s);
  // A mesh built again has the same repairs first: only what follows is new.
  const size_t passed = s.mesh.warnings.size();
  lightVertices(s, options);
  recheckGather(s);
  passOn(s.mesh.warnings, passed, options);
  return s;
}

double timeLeft(const MeshedScene& scene) {
  if (!(scene.settings.timeLimit > 0)) return 0;
  const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - scene.started).count();
  return std::max(kNoTimeLeft, scene.settings.timeLimit - spent);
}

SolverOptions solverOptions(const Settings& settings, size_t patches) {
  SolverOptions options;
  options.tolerance = settings.tolerance;
  options.maxShots = settings.maxShots;
  if (!options.maxShots && settings.shotsPerPatch > 0)
    options.maxShots = std::max(1L, long(std::ceil(settings.shotsPerPatch * double(patches))));
  options.timeLimit = settings.timeLimit;
  options.overshoot = settings.overshoot;
  options.emitterSamples = settings.emitterSamples;
  options.shooterSamples = settings.shooterSamples;
  options.proximitySamples = settings.proximitySamples;
  options.clusters = settings.clusterShooters;
  options.followingResolution = settings.resolutionFollowsPower ? settings.hemicubeResolution : 0;
  options.factorCacheBytes = size_t(settings.factorCacheMb * 1024 * 1024);
  return options;
}

std::unique_ptr<HemicubeFactors> hemicubeFactors(const MeshedScene& s, int workers) {
  // With the gather on, the shots are only its start: their hemicubes draw flat regions too.
  return std::make_unique<HemicubeFactors>(s.mesh, s.settings.hemicubeResolution, s.scene.diagonal(),
                                           s.settings.seed, workers, s.settings.emitterHemicubeResolution, s.gather);
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
  if (gather && scene_.gather) gatherAtVertices(b);
  return b;
}

void RadiositySolve::gatherAtVertices(Solution& b) const {
  const PatchMesh& mesh = scene_.mesh;
  std::vector<glm::dvec3> start = shownAtVertices(scene_, b);
  const std::vector<glm::dvec3> emission = vertexEmission(mesh);
  for (size_t v = 0; v < start.size(); ++v) start[v] = glm::max(start[v] - emission[v], glm::dvec3(0.0));
  GatherOptions options = gatherOptions(scene_);
  options.workers = workers_;
  const std::vector<glm::dvec3>* direct = b.direct ? &b.direct->vertex : nullptr;
  const GatherRows* rendered = scene_.gatherAhead ? &scene_.gatherAhead->rows() : nullptr;
  std::vector<glm::dvec3> gathered =
      finalGather(mesh, scene_.base.get(), scene_.scene.diagonal(), start, direct, options, &b.gather, rendered);
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
