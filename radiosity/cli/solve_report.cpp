#include "radiosity/cli/solve_report.h"

namespace rad::cli {
namespace {

Json settingsBlock(const Settings& settings) {
  const SolverOptions options = solverOptions(settings);
  Json s;
  s["max_element_edge"] = settings.maxElementEdge;
  s["max_patch_edge"] = settings.maxPatchEdge;
  s["cut_contacts"] = settings.cutContacts;
  s["hemicube_resolution"] = settings.hemicubeResolution;
  s["emitter_hemicube_resolution"] = settings.emitterHemicubeResolution;
  s["tolerance"] = settings.tolerance;
  s["seed"] = settings.seed;
  s["max_shots"] = settings.maxShots;
  s["time_limit"] = settings.timeLimit;
  s["overshoot"] = settings.overshoot;
  s["emitter_samples"] = options.emitterSamples;
  s["shooter_samples"] = options.shooterSamples;
  s["proximity_samples"] = options.proximitySamples;
  s["factor_cache_mb"] = settings.factorCacheMb;
  s["adaptive"] = settings.adaptive;
  s["min_element_edge"] = settings.minElementEdge;
  s["contrast"] = settings.contrast;
  s["vertex_direct"] = settings.vertexDirect;
  s["max_elements"] = settings.maxElements;
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
          {"rays", direct ? direct->rays() : 0}};
}

/// What contacts cut away: the parts of surfaces other surfaces enclose (a floor under a
/// block), which could neither receive nor send light; and their total area.
Json cutAwayList(const MeshedScene& scene, double& area) {
  Json cutAway = Json::array();
  area = 0;
  for (const auto& c : scene.mesh.cutAway) {
    Json by = Json::array();
    for (int s : c.enclosedBy) by.push_back(scene.scene.surfaces[s].name);
    cutAway.push_back({{"surface", scene.scene.surfaces[c.surface].name}, {"area", c.area}, {"enclosed_by", by}});
    area += c.area;
  }
  return cutAway;
}

/// What the scene did not need: black elements receive nothing (they only occlude), and
/// patches whose unshot power never became the largest never shot.
Json leftOutBlock(const MeshedScene& scene, const ProgressiveSolver& solver) {
  const PatchMesh& mesh = scene.mesh;
  int black = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) black += mesh.reflectance(e) == glm::dvec3(0.0);
  double cutArea = 0;
  Json cutAway = cutAwayList(scene, cutArea);
  return {{"black_elements_receive_nothing", black},
          {"patches_never_shot", solver.patchesNeverShot()},
          {"channels_solved", solver.grey() ? 1 : 3},
          {"area_cut_away", cutArea},
          {"cut_away", cutAway},
          {"contact_lines", mesh.contactLines},
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
  if (e.worstPoint >= 0) {
    const ReferencePoint& p = truth.points()[size_t(e.worstPoint)];
    j["worst"] = {{"surface", p.surface}, {"tag", p.tag}, {"position", rgb(p.position)},
                  {"reference", rgb(p.B)}, {"shown", rgb(e.worstShown)}, {"relative_error", e.worst}};
  }
  Json table = Json::array();
  for (const auto& s : e.perSurface)
    table.push_back({{"surface", s.name}, {"points", s.points}, {"channels_used", s.channels},
                     {"rms", s.channels ? Json(s.rms) : Json()}, {"mean", s.channels ? Json(s.mean) : Json()}});
  j["per_surface"] = table;
  return j;
}

Json solveReport(const MeshedScene& scene, const RadiositySolve& solve, const Solution& solution) {
  const ProgressiveSolver& solver = solve.solver();
  Json report;
  report["scene"] = scene.scene.path;
  report["settings"] = settingsBlock(scene.settings);
  report["adaptive"] = adaptiveBlock(scene.adaptive);
  report["direct_light"] = directLightBlock(scene.direct.get());
  report["counts"] = countsBlock(scene, solver);
  report["shots"] = solver.shots();
  report["hemicubes"] = solver.hemicubes();
  report["factor_cache_bytes"] = solver.cachedBytes();
  report["seconds"] = solver.seconds();
  report["stop_reason"] = stopName(solver.stopReason());
  report["exposure"] = exposureOf(scene, solution);
  report["ambient_applied"] = !solution.converged;
  report["ambient"] = rgb(solution.ambient);
  report["negative_clamped"] = solution.clamped;
  report["camera"] = cameraBlock(cameraOf(scene.scene));
  report["energy"] = energyBlock(solver.ledger());
  return report;
}

}  // namespace rad::cli
