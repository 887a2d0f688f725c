#include "radiosity/cli/solve_report.h"

namespace rad::cli {
namespace {

/// The settings of shooting: hemicubes, stop conditions, shooting points and the factor cache.
void addShootingSettings(Json& s, const Settings& settings, const Shooting& shooting) {
  s["hemicube_resolution"] = shooting.hemicubeResolution;
  s["emitter_hemicube_resolution"] = shooting.emitterHemicubeResolution;
  s["tolerance"] = shooting.tolerance;
  s["seed"] = settings.seed;
  s["max_shots"] = settings.maxShots;
  s["shots_per_patch"] = shooting.shotsPerPatch;
  s["time_limit"] = settings.timeLimit;
  s["overshoot"] = settings.overshoot;
  s["emitter_samples"] = shooting.emitterSamples;
  s["shooter_samples"] = settings.shooterSamples;
  s["proximity_samples"] = settings.proximitySamples;
  s["cluster_shooters"] = settings.clusterShooters;
  s["resolution_follows_power"] = settings.resolutionFollowsPower;
  s["factor_cache_mb"] = settings.factorCacheMb;
}

/// The settings of adaptive refinement, the direct light at the vertices and the element cap.
void addRefinementSettings(Json& s, const Settings& settings) {
  s["adaptive"] = settings.adaptive;
  s["min_element_edge"] = settings.minElementEdge;
  s["contrast"] = settings.contrast;
  s["vertex_direct"] = settings.vertexDirect;
  s["final_gather"] = settings.finalGather;
  s["gather_resolution"] = settings.gatherResolution;
  s["gather_accuracy"] = settings.gatherAccuracy;
  s["quality"] = settings.quality == Quality::Draft ? "draft" : settings.quality == Quality::Final ? "final" : "default";
  s["max_elements"] = settings.maxElements;
}

/// The settings, shooting as the gather's plan says (its start, or the answer's).
Json settingsBlock(const Settings& settings, const Shooting& shooting) {
  Json s;
  s["max_element_edge"] = settings.maxElementEdge;
  s["max_patch_edge"] = settings.maxPatchEdge;
  s["cut_contacts"] = settings.cutContacts;
  s["fix_facing"] = settings.fixFacing;
  addShootingSettings(s, settings, shooting);
  addRefinementSettings(s, settings);
  return s;
}

/// What refinement did.
Json adaptiveBlock(const AdaptiveStats& adaptive) {
  return {{"rounds", adaptive.rounds},
          {"elements_before", adaptive.elementsBefore},
          {"elements_after", adaptive.elementsAfter},
          {"marked", adaptive.marked},
          {"exposure_estimate", adaptive.exposure},
          {"seconds", adaptive.seconds}};
}

/// The rays behind the direct light shown.
Json directLightBlock(const DirectLight* direct) {
  return {{"at_vertices", bool(direct)},
          {"light_samples", direct ? direct->samples() : 0},
          {"rays", direct ? direct->rays() : 0},
          {"seen_whole", direct ? direct->seenWhole() : 0}};
}

/// The names of some surfaces, as a JSON array.
Json surfaceNames(const Scene& scene, const std::vector<int>& surfaces) {
  Json names = Json::array();
  for (int s : surfaces) names.push_back(scene.surfaces[s].name);
  return names;
}

/// What contacts cut away: the parts of surfaces other surfaces enclose (a floor under a
/// block), which could neither receive nor send light; and their total area.
Json cutAwayList(const MeshedScene& scene, double& area) {
  Json cutAway = Json::array();
  area = 0;
  for (const auto& c : scene.mesh.cutAway) {
    cutAway.push_back({{"surface", scene.scene.surfaces[c.surface].name},
                       {"area", c.area},
                       {"enclosed_by", surfaceNames(scene.scene, c.enclosedBy)}});
    area += c.area;
  }
  return cutAway;
}

/// The elements that reflect nothing.
int blackElements(const PatchMesh& mesh) {
  int black = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) black += mesh.reflectance(e) == glm::dvec3(0.0);
  return black;
}

/// The vertices on seams: each side of a contact line across a surface has its own.
int seamVertices(const PatchMesh& mesh) {
  int seam = 0;
  for (auto v : mesh.mesh.vertices()) seam += mesh.seam(v);
  return seam;
}

/// What the scene did not need: black elements receive nothing (they only occlude), and
/// patches whose unshot power never became the largest never shot.
Json leftOutBlock(const MeshedScene& scene, const ProgressiveSolver& solver) {
  const PatchMesh& mesh = scene.mesh;
  const int black = blackElements(mesh);
  double cutArea = 0;
  Json cutAway = cutAwayList(scene, cutArea);
  return {{"black_elements_receive_nothing", black},
          {"patches_never_shot", solver.patchesNeverShot()},
          {"channels_solved", solver.grey() ? 1 : 3},
          {"area_cut_away", cutArea},
          {"cut_away", cutAway},
          {"contact_lines", mesh.contactLines},
          {"seam_vertices", seamVertices(mesh)},
          {"full_matrix", "not built (progressive path)"}};
}

Json countsBlock(const MeshedScene& scene, const ProgressiveSolver& solver) {
  Json counts;
  counts["surfaces"] = scene.scene.surfaces.size();
  counts["patches"] = scene.mesh.patches.size();
  counts["elements"] = scene.mesh.elementCount();
  counts["vertices"] = scene.mesh.mesh.n_vertices();
  counts["left_out"] = leftOutBlock(scene, solver);
  return counts;
}

Json cameraBlock(const Camera& camera) {
  return {{"eye", rgb(camera.eye)}, {"target", rgb(camera.target)}, {"up", rgb(camera.up)},
          {"fov_y_deg", camera.fovYDeg}};
}

Json energyBlock(const EnergyLedger& l) {
  return {{"emitted", rgb(l.emitted)}, {"absorbed", rgb(l.absorbed)}, {"escaped", rgb(l.escaped)},
          {"unshot", rgb(l.unshot)}, {"residual", l.residual()}};
}

/// The point of the largest relative error: where, the reference, what is shown and the error.
Json worstBlock(const ErrorSummary& e, const TrueError& truth) {
  const ReferencePoint& p = truth.points()[size_t(e.worstPoint)];
  return {{"surface", p.surface}, {"tag", p.tag}, {"position", rgb(p.position)},
          {"reference", rgb(p.B)}, {"shown", rgb(e.worstShown)}, {"relative_error", e.worst}};
}

/// The error per surface (null RMS and mean where no channel was used).
Json perSurfaceTable(const ErrorSummary& e) {
  Json table = Json::array();
  for (const auto& s : e.perSurface)
    table.push_back({{"surface", s.name}, {"points", s.points}, {"channels_used", s.channels},
                     {"rms", s.channels ? Json(s.rms) : Json()}, {"mean", s.channels ? Json(s.mean) : Json()}});
  return table;
}

/// What the solver did: shots, hemicubes, cache, time and why it stopped.
void addRunFields(Json& report, const ProgressiveSolver& solver) {
  report["shots"] = solver.shots();
  report["cluster_shots"] = solver.clusterShots();
  report["coarser_shots"] = solver.coarserShots();
  report["hemicubes"] = solver.hemicubes();
  report["factor_cache_bytes"] = solver.cachedBytes();
  report["seconds"] = solver.seconds();
  report["stop_reason"] = stopName(solver.stopReason());
}

/// How the solution is shown: exposure, the ambient term and the clamped elements.
void addDisplayFields(Json& report, const MeshedScene& scene, const Solution& solution) {
  report["exposure"] = exposureOf(scene, solution);
  report["ambient_applied"] = !solution.converged && !solution.gathered;
  report["ambient"] = rgb(solution.ambient);
  report["negative_clamped"] = solution.clamped;
}

/// What the final gather did (null without one; given up at the time limit: how long it ran).
Json gatherBlock(const Solution& solution) {
  const GatherStats& g = solution.gather;
  if (g.timedOut) return {{"timed_out", true}, {"hemicube_seconds", g.hemicubeSeconds}};
  if (!solution.gathered) return Json();
  return {{"points", g.points},           {"own_hemicubes", g.ownHemicubes}, {"doubted", g.doubted},
          {"interpolated", g.interpolated}, {"factors", g.factors},
          {"iterated", g.iterated},       {"iterations", g.iterations},
          {"residual", g.residual},       {"hemicube_seconds", g.hemicubeSeconds},
          {"rendered_ahead", g.renderedAhead}, {"solve_seconds", g.solveSeconds}};
}

}  // namespace

Json rgb(const glm::dvec3& c) { return Json::array({c.x, c.y, c.z}); }

const char* stopName(ProgressiveSolver::Stop s) {
  switch (s) {
    case ProgressiveSolver::Stop::MaxShots: return "max_shots";
    case ProgressiveSolver::Stop::TimeLimit: return "time_limit";
    default: return "tolerance";
  }
}

Json errorBlock(const ErrorSummary& e, const TrueError& truth, const std::string& file) {
  Json j;
  j["definition"] = "relative error (shown - reference) / reference per channel of the Gouraud vertex "
                    "radiosity (ambient term included while unconverged) at the reference's points; "
                    "channels below 1 % of the brightest reference value in that channel skipped";
  j["reference"] = file;
  j["points"] = truth.points().size();
  j["points_not_in_result"] = truth.notInResult();
  j["channels_used"] = e.used;
  j["channels_skipped"] = e.skipped;
  j["rms"] = e.rms;
  j["rms_rgb"] = rgb(e.rmsRgb);
  j["mean_rgb"] = rgb(e.meanRgb);
  j["reference_noise_rms"] = e.referenceNoise;
  if (e.worstPoint >= 0) j["worst"] = worstBlock(e, truth);
  j["per_surface"] = perSurfaceTable(e);
  return j;
}

Json pointsTable(const TrueError& truth, const std::vector<glm::dvec3>& shown) {
  Json table = Json::array();
  for (size_t i = 0; i < shown.size(); ++i) {
    const ReferencePoint& p = truth.points()[i];
    table.push_back({{"surface", p.surface}, {"tag", p.tag}, {"position", rgb(p.position)},
                     {"reference", rgb(p.B)}, {"standard_error", rgb(p.standardError)}, {"shown", rgb(shown[i])}});
  }
  return table;
}

Json stagesTable(const StageTimes& stages) {
  Json table = Json::array();
  for (const StageTime& s : stages.list())
    table.push_back({{"name", s.name}, {"seconds", s.seconds}, {"peak_mib", s.peakMiB}});
  return table;
}

Json solveReport(const MeshedScene& scene, const RadiositySolve& solve, const Solution& solution) {
  const ProgressiveSolver& solver = solve.solver();
  Json report;
  report["scene"] = scene.scene.path;
  report["settings"] = settingsBlock(scene.settings, scene.gather.shooting);
  report["adaptive"] = adaptiveBlock(scene.adaptive);
  report["direct_light"] = directLightBlock(scene.direct.get());
  report["counts"] = countsBlock(scene, solver);
  addRunFields(report, solver);
  addDisplayFields(report, scene, solution);
  report["final_gather"] = gatherBlock(solution);
  report["camera"] = cameraBlock(cameraOf(scene.scene));
  report["energy"] = energyBlock(solver.ledger());
  return report;
}

}  // namespace rad::cli
