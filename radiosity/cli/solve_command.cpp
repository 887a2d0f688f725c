// radiosity solve SCENE -o RESULT.ply [--report R.json]: the main job.
#include <cmath>

#include <glm/common.hpp>
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "mesh/error.h"
#include "mesh/output_file.h"
#include "mesh/patch_mesh.h"
#include "mesh/settings.h"
#include "radiosity/cli/commands.h"
#include "radiosity/progressive_solver.h"
#include "radiosity/reference_solver.h"
#include "radiosity/result.h"
#include "radiosity/true_error.h"

namespace rad::cli {
namespace {

/// History rows at least this often (seconds), and at shot counts growing by this factor.
constexpr double kHistorySeconds = 0.05;
constexpr double kHistoryShotGrowth = 1.25;
/// Progress line refresh on a terminal (seconds).
constexpr double kProgressSeconds = 0.1;

struct SolveOptions {
  std::string scene, output, report, reference, fixedPoint;
  SolverBlock flags;
};

/// What the history measures: the true error against an independent reference, and the
/// distance to the direct solution of the same mesh and factors (convergence, not error).
struct Measures {
  std::unique_ptr<TrueError> truth;
  std::vector<glm::dvec3> fixedPoint;
};

using Json = nlohmann::ordered_json;

Json rgb(const glm::dvec3& c) { return Json::array({c.x, c.y, c.z}); }

const char* stopName(ProgressiveSolver::Stop s) {
  switch (s) {
    case ProgressiveSolver::Stop::MaxShots: return "max_shots";
    case ProgressiveSolver::Stop::TimeLimit: return "time_limit";
    default: return "tolerance";
  }
}

Json historyRow(const ProgressiveSolver& solver, const SolvableScene& s, const Measures& m) {
  Json row;
  row["seconds"] = solver.seconds();
  row["shots"] = solver.shots();
  row["unshot_fraction"] = solver.unshotFraction();
  row["residual"] = solver.ledger().residual();
  if (m.truth) {
    const ErrorSummary e = trueErrorNow(solver, s, *m.truth);
    row["error"] = e.rms;
    row["error_rms_rgb"] = rgb(e.rmsRgb);
    row["error_mean_rgb"] = rgb(e.meanRgb);
  }
  if (!m.fixedPoint.empty()) row["fixed_point_distance"] = relativeError(s.mesh, solver.radiosity(), m.fixedPoint);
  return row;
}

/// The report's "error" block: the definition, the reference and the summary.
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

void runSolve(const SolveOptions& o) {
  checkOutputPath(o.output);
  if (!o.report.empty()) checkOutputPath(o.report);
  // The reference is read before any work: a bad file fails at once.
  std::vector<ReferencePoint> referencePoints;
  if (!o.reference.empty()) {
    const bool ply = o.reference.size() >= 4 && o.reference.compare(o.reference.size() - 4, 4, ".ply") == 0;
    if (o.reference == "direct" || ply)
      throw inputError("--reference " + o.reference,
                       "a reference CSV written by 'radiosity reference' (for the distance to the "
                       "direct solution of the same mesh and factors, use --fixed-point)", o.reference);
    referencePoints = readReferenceFile(o.reference).points;
  }
  SolvableScene solvable = loadSolvable(o.scene, o.flags);
  const auto& [scene, settings, mesh, direct, adaptive, base] = solvable;
  SolverOptions options = solverOptions(settings);
  std::unique_ptr<HemicubeFactors> hemicubes = hemicubeFactors(solvable, 0);
  HemicubeFactors& factors = *hemicubes;
  // The fixed point first, so that the solve's own clock does not count it.
  Measures measures;
  if (o.fixedPoint == "direct")
    measures.fixedPoint = TransportMatrix(mesh, factors, options).solveDirect();
  else if (!o.fixedPoint.empty())
    measures.fixedPoint = readResultRadiosity(o.fixedPoint, mesh, scene.diagonal());
  if (!referencePoints.empty()) measures.truth = std::make_unique<TrueError>(mesh, scene, std::move(referencePoints), o.reference);
  ProgressiveSolver solver(mesh, factors, options);

  // Shoot, keeping the history and showing progress on a terminal.
  Json history = Json::array();
  history.push_back(historyRow(solver, solvable, measures));
  double nextRowShots = 1, lastRowSeconds = 0, lastProgress = 0;
  const bool terminal = isatty(STDERR_FILENO);
  while (solver.step()) {
    double t = solver.seconds();
    if (solver.shots() >= nextRowShots || t - lastRowSeconds >= kHistorySeconds) {
      history.push_back(historyRow(solver, solvable, measures));
      nextRowShots = std::ceil(solver.shots() * kHistoryShotGrowth);
      lastRowSeconds = t;
    }
    if (terminal && t - lastProgress >= kProgressSeconds) {
      std::fprintf(stderr, "\rradiosity: %ld shots, unshot %.2e, %.1f s   ", solver.shots(),
                   solver.unshotFraction(), t);
      lastProgress = t;
    }
  }
  if (terminal) std::fprintf(stderr, "\n");
  // The last row measures what is baked.
  if (history.back()["shots"] != solver.shots()) history.push_back(historyRow(solver, solvable, measures));

  // Bake: unconverged solutions show the ambient term in their display colours.
  const bool converged = solver.stopReason() == ProgressiveSolver::Stop::Tolerance;
  const Baked baked = bake(solver, bool(direct));
  const std::vector<glm::dvec3>& B = baked.B;
  const glm::dvec3 ambient = baked.ambient;
  const int clamped = baked.clamped;
  if (clamped)
    std::fprintf(stderr, "radiosity: warning: %d elements had a negative channel (overshooting "
                         "before convergence), set to 0\n", clamped);
  double exposure = settings.exposure ? *settings.exposure : autoExposure(mesh, B);
  Camera camera = scene.camera ? *scene.camera : defaultCamera(scene);

  Json report;
  report["scene"] = scene.path;
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
  report["settings"] = s;
  // What refinement did, and the rays behind it and behind the direct light shown.
  report["adaptive"] = {{"rounds", adaptive.rounds},
                        {"elements_before", adaptive.elementsBefore},
                        {"elements_after", adaptive.elementsAfter},
                        {"marked", adaptive.marked},
                        {"exposure_estimate", adaptive.exposure},
                        {"seconds", adaptive.seconds}};
  report["direct_light"] = {{"at_vertices", bool(direct)},
                            {"light_samples", direct ? direct->samples() : 0},
                            {"rays", direct ? direct->rays() : 0}};
  Json counts;
  counts["surfaces"] = scene.surfaces.size();
  counts["patches"] = mesh.patches.size();
  counts["elements"] = mesh.elementCount();
  counts["vertices"] = mesh.mesh.n_vertices();
  // What the scene did not need: black elements receive nothing (they only occlude), and
  // patches whose unshot power never became the largest never shot.
  int black = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) black += mesh.reflectance(e) == glm::dvec3(0.0);
  // What contacts cut away: the parts of surfaces other surfaces enclose (a floor under a
  // block), which could neither receive nor send light.
  Json cutAway = Json::array();
  double cutArea = 0;
  for (const auto& c : mesh.cutAway) {
    Json by = Json::array();
    for (int s : c.enclosedBy) by.push_back(scene.surfaces[s].name);
    cutAway.push_back({{"surface", scene.surfaces[c.surface].name}, {"area", c.area},
                       {"enclosed_by", by}});
    cutArea += c.area;
  }
  counts["left_out"] = {{"black_elements_receive_nothing", black},
                        {"patches_never_shot", solver.patchesNeverShot()},
                        {"channels_solved", solver.grey() ? 1 : 3},
                        {"area_cut_away", cutArea},
                        {"cut_away", cutAway},
                        {"contact_lines", mesh.contactLines},
                        {"full_matrix", "not built (progressive path)"}};
  report["counts"] = counts;
  report["shots"] = solver.shots();
  report["hemicubes"] = solver.hemicubes();
  report["factor_cache_bytes"] = solver.cachedBytes();
  report["seconds"] = solver.seconds();
  report["stop_reason"] = stopName(solver.stopReason());
  report["exposure"] = exposure;
  report["ambient_applied"] = !converged;
  report["ambient"] = rgb(ambient);
  report["negative_clamped"] = clamped;
  report["camera"] = {{"eye", rgb(camera.eye)}, {"target", rgb(camera.target)},
                      {"up", rgb(camera.up)}, {"fov_y_deg", camera.fovYDeg}};
  const EnergyLedger& l = solver.ledger();
  report["energy"] = {{"emitted", rgb(l.emitted)}, {"absorbed", rgb(l.absorbed)},
                      {"escaped", rgb(l.escaped)}, {"unshot", rgb(l.unshot)},
                      {"residual", l.residual()}};
  std::unique_ptr<ErrorSummary> trueError;
  if (measures.truth) {
    trueError = std::make_unique<ErrorSummary>(trueErrorNow(solver, solvable, *measures.truth));
    report["error"] = errorBlock(*trueError, *measures.truth, o.reference);
  }
  if (!measures.fixedPoint.empty()) {
    report["fixed_point"] = o.fixedPoint;
    report["fixed_point_distance"] = relativeError(mesh, solver.radiosity(), measures.fixedPoint);
  }
  report["history"] = history;

  // Outputs: each through a temporary file; the report last, so a report means a result.
  const auto vertexLight = vertexDirect(solver, solvable);
  writeResult(o.output, mesh, B, ambient, exposure, camera, vertexLight.get());
  if (!o.report.empty())
    writeFileAtomically(o.report, [&](std::ostream& out) { out << report.dump(2) << "\n"; });
  std::fprintf(stderr, "radiosity: %s after %ld shots in %.2f s (unshot %.2e, %s); wrote %s\n",
               converged ? "converged" : "stopped", solver.shots(), solver.seconds(),
               solver.unshotFraction(), stopName(solver.stopReason()), o.output.c_str());
  if (trueError)
    std::fprintf(stderr, "radiosity: true error (RMS of the relative error at %d channel values of %zu points, "
                         "against %s): %.2f %% (reference noise %.2f %%), mean %+.2f/%+.2f/%+.2f %%\n",
                 trueError->used, measures.truth->points().size(), o.reference.c_str(), 100 * trueError->rms,
                 100 * trueError->referenceNoise, 100 * trueError->meanRgb.x, 100 * trueError->meanRgb.y,
                 100 * trueError->meanRgb.z);
}

}  // namespace

// Overshooting can leave a slightly negative channel mid-solve; a result never carries one.
// With direct light from rays at the vertices, the emission not yet shot is already shown,
// so the ambient term leaves it out.
Baked bake(const ProgressiveSolver& solver, bool directAtVertices) {
  Baked b;
  const bool converged = solver.stopReason() == ProgressiveSolver::Stop::Tolerance;
  b.ambient = converged ? glm::dvec3(0.0) : glm::max(solver.ambient(directAtVertices), glm::dvec3(0.0));
  b.B = solver.radiosity();
  for (auto& x : b.B)
    if (x.x < 0 || x.y < 0 || x.z < 0) {
      ++b.clamped;
      x = glm::max(x, glm::dvec3(0.0));
    }
  return b;
}

std::unique_ptr<VertexDirect> vertexDirect(const ProgressiveSolver& solver, const SolvableScene& s) {
  if (!s.direct) return nullptr;
  return std::make_unique<VertexDirect>(VertexDirect{solver.direct(), s.direct->radiosity(), s.base.get()});
}

/// The true error of what a viewer would show now.
ErrorSummary trueErrorNow(const ProgressiveSolver& solver, const SolvableScene& s, const TrueError& truth) {
  const Baked b = bake(solver, bool(s.direct));
  const auto direct = vertexDirect(solver, s);
  return truth.measure(shownVertexRadiosity(s.mesh, b.B, b.ambient, direct.get()));
}

Command addSolveCommand(CLI::App& app) {
  auto o = std::make_shared<SolveOptions>();
  CLI::App* sub = app.add_subcommand(
      "solve", "Solve the scene by progressive refinement and write the result mesh (vertex "
               "radiosities as colours) and, optionally, a JSON report");
  sub->add_option("scene", o->scene, "Scene file (JSON, version 1)")->required();
  sub->add_option("-o,--output", o->output, "Result mesh (binary PLY)")->required();
  sub->add_option("--report", o->report, "Report file (JSON): settings, counts, energy ledger, history");
  addMeshFlags(*sub, o->flags);
  addSolverFlags(*sub, o->flags);
  sub->add_option("--tolerance", o->flags.tolerance,
                  "Stop when unshot/emitted power falls below this (solver.tolerance; default 1e-3)")
      ->check(CLI::Range(1e-300, 1.0));
  sub->add_option("--max-shots", o->flags.maxShots, "Stop after this many shots (solver.max_shots)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--time-limit", o->flags.timeLimit, "Stop after this many seconds (solver.time_limit)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--overshoot", o->flags.overshoot,
                  "Overshooting factor ω in [1, 2] (solver.overshoot; default 1.3, measured; 1: plain shooting)")
      ->check(CLI::Range(1.0, 2.0));
  sub->add_option("--reference", o->reference,
                  "Measure the true error against a reference CSV from 'radiosity reference': the "
                  "report's history and its 'error' block then hold the relative error of what a "
                  "viewer shows at the reference's points");
  sub->add_option("--fixed-point", o->fixedPoint,
                  "Measure convergence (not error) to 'direct' (the full system solved from the same "
                  "hemicubes first) or an earlier result PLY of the same scene and mesh settings: "
                  "the history's fixed_point_distance, relative L2 over elements");
  sub->add_option("--exposure", o->flags.exposure,
                  "Display exposure K (solver.exposure; default: automatic, see README)")
      ->check(CLI::PositiveNumber);
  return {sub, [o] { runSolve(*o); }};
}

}  // namespace rad::cli
