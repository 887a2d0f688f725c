// radiosity solve SCENE -o RESULT.ply [--report R.json]: the main job.
#include <cmath>

#include <glm/common.hpp>
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "mesh/base/error.h"
#include "mesh/base/output_file.h"
#include "radiosity/cli/commands.h"
#include "radiosity/cli/solve_report.h"
#include "radiosity/reference_solver.h"
#include "radiosity/result.h"
#include "radiosity/solve.h"
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

/// Whether a file name ends in .ply (a result, not a reference).
bool isPly(const std::string& path) {
  return path.size() >= 4 && path.compare(path.size() - 4, 4, ".ply") == 0;
}

/// The reference's points, read before any work: a bad file fails at once.
std::vector<ReferencePoint> readReference(const std::string& reference) {
  if (reference.empty()) return {};
  if (reference == "direct" || isPly(reference))
    throw inputError("--reference " + reference,
                     "a reference CSV written by 'radiosity reference' (for the distance to the "
                     "direct solution of the same mesh and factors, use --fixed-point)", reference);
  return readReferenceFile(reference).points;
}

/// The fixed point first, so that the solve's own clock does not count it.
std::vector<glm::dvec3> fixedPoint(const std::string& which, const MeshedScene& scene) {
  if (which.empty()) return {};
  if (which != "direct") return readResultRadiosity(which, scene.mesh, scene.scene.diagonal());
  const std::unique_ptr<HemicubeFactors> factors = hemicubeFactors(scene);
  return TransportMatrix(scene.mesh, *factors, solverOptions(scene)).solveByLU();
}

/// A history row's true error: the RMS, and per channel the RMS and mean.
void addTrueError(Json& row, const ErrorSummary& e) {
  row["error"] = e.rms;
  row["error_rms_rgb"] = rgb(e.rmsRgb);
  row["error_mean_rgb"] = rgb(e.meanRgb);
}

Json historyRow(const RadiositySolve& solve, const MeshedScene& scene, const Measures& m) {
  const ProgressiveSolver& solver = solve.solver();
  Json row;
  row["seconds"] = solver.seconds();
  row["shots"] = solver.shots();
  row["unshot_fraction"] = solver.unshotFraction();
  row["residual"] = solver.ledger().residual();
  if (m.truth) addTrueError(row, trueErrorNow(solve, scene, *m.truth));
  if (!m.fixedPoint.empty()) row["fixed_point_distance"] = relativeError(scene.mesh, solver.radiosity(), m.fixedPoint);
  return row;
}

/// The progress line on a terminal, overwritten in place.
void printProgress(const ProgressiveSolver& solver, double t) {
  std::fprintf(stderr, "\rradiosity: %ld shots, unshot %.2e, %.1f s   ", solver.shots(), solver.unshotFraction(), t);
}

/// Shoots to a stop condition, keeping the history and showing progress on a terminal; the
/// rows measure the progressive solution (the report's error block, what the final gather made).
Json shoot(RadiositySolve& solve, const MeshedScene& scene, const Measures& measures) {
  const ProgressiveSolver& solver = solve.solver();
  Json history = Json::array({historyRow(solve, scene, measures)});
  double nextRowShots = 1, lastRowSeconds = 0, lastProgress = 0;
  const bool terminal = isatty(STDERR_FILENO);
  while (solve.step()) {
    const double t = solver.seconds();
    if (solver.shots() >= nextRowShots || t - lastRowSeconds >= kHistorySeconds) {
      history.push_back(historyRow(solve, scene, measures));
      nextRowShots = std::ceil(solver.shots() * kHistoryShotGrowth);
      lastRowSeconds = t;
    }
    if (terminal && t - lastProgress >= kProgressSeconds) printProgress(solver, t), lastProgress = t;
  }
  if (terminal) std::fprintf(stderr, "\n");
  if (history.back()["shots"] != solver.shots()) history.push_back(historyRow(solve, scene, measures));
  return history;
}

void printOutcome(const RadiositySolve& solve, const Solution& solution, const std::string& output) {
  const ProgressiveSolver& solver = solve.solver();
  if (solution.clamped)
    std::fprintf(stderr, "radiosity: warning: %d elements had a negative channel (overshooting "
                         "before convergence), set to 0\n", solution.clamped);
  if (solution.gather.timedOut)
    std::fprintf(stderr, "radiosity: warning: final gather given up at the time limit (%.2f s of hemicubes); the "
                         "progressive solution is shown, with its ambient term\n", solution.gather.hemicubeSeconds);
  if (solution.gathered) {
    const GatherStats& g = solution.gather;
    std::fprintf(stderr, "radiosity: progressive start %ld shots in %.2f s (unshot %.2e, %s); final gather at %d "
                         "vertices (%d added by refinement, %d where gathering vertices near them differed; %d others took their light): hemicubes %.2f s%s, %d iterations (residual %.1e) in %.2f s; wrote %s\n",
                 solver.shots(), solver.seconds(), solver.unshotFraction(), stopName(solver.stopReason()), g.points,
                 g.ownHemicubes, g.doubted, g.interpolated, g.hemicubeSeconds, g.renderedAhead ? " (beside the rays and shots)" : "", g.iterations, g.residual,
                 g.solveSeconds, output.c_str());
    return;
  }
  std::fprintf(stderr, "radiosity: %s after %ld shots in %.2f s (unshot %.2e, %s); wrote %s\n",
               solution.converged ? "converged" : "stopped", solver.shots(), solver.seconds(),
               solver.unshotFraction(), stopName(solver.stopReason()), output.c_str());
}

void printTrueError(const ErrorSummary& e, const TrueError& truth, const std::string& reference) {
  std::fprintf(stderr, "radiosity: true error (RMS of the relative error at %d channel values of %zu points, "
                       "against %s): %.2f %% (reference noise %.2f %%), mean %+.2f/%+.2f/%+.2f %%\n",
               e.used, truth.points().size(), reference.c_str(), 100 * e.rms, 100 * e.referenceNoise,
               100 * e.meanRgb.x, 100 * e.meanRgb.y, 100 * e.meanRgb.z);
}

/// The measures asked for: the true error against the reference's points, the fixed point.
Measures measuresFor(const SolveOptions& o, const MeshedScene& scene, std::vector<ReferencePoint> points) {
  Measures m;
  m.fixedPoint = fixedPoint(o.fixedPoint, scene);
  if (!points.empty()) m.truth = std::make_unique<TrueError>(scene.mesh, scene.scene, std::move(points), o.reference);
  return m;
}

/// The report's closing measures: the true error of what is baked, and the fixed-point distance.
void addMeasures(Json& report, const SolveOptions& o, const Measures& m, const MeshedScene& scene,
                 const RadiositySolve& solve, const Solution& solution) {
  if (m.truth) {
    const std::vector<glm::dvec3> shown = shownAtVertices(scene, solution);
    const ErrorSummary e = m.truth->measure(shown);
    report["error"] = errorBlock(e, *m.truth, o.reference);
    report["error"]["at_points"] = pointsTable(*m.truth, m.truth->shown(shown));
    printTrueError(e, *m.truth, o.reference);
  }
  if (!m.fixedPoint.empty()) {
    report["fixed_point"] = o.fixedPoint;
    report["fixed_point_distance"] = relativeError(scene.mesh, solve.solver().radiosity(), m.fixedPoint);
  }
}

void runSolve(const SolveOptions& o) {
  checkOutputPath(o.output);
  if (!o.report.empty()) checkOutputPath(o.report);
  std::vector<ReferencePoint> referencePoints = readReference(o.reference);
  StageTimes stages;
  // Converging to the direct solution of the patches' own factors, every patch shoots alone,
  // every shot at the one resolution.
  SolverBlock flags = o.flags;
  if (o.fixedPoint == "direct") flags.clusterShooters = flags.resolutionFollowsPower = false;
  const MeshedScene scene = loadAndMesh(o.scene, loadSceneToSolve, flags, true, stages);
  auto start = StageTimes::Clock::now();
  const Measures measures = measuresFor(o, scene, std::move(referencePoints));
  if (!measures.fixedPoint.empty()) start = stages.add("fixed point", start);
  RadiositySolve solve(scene);
  Json history = shoot(solve, scene, measures);
  start = stages.add("shooting", start);
  const Solution solution = solve.bake();
  start = stages.add(solution.gathered ? "final gather" : "baking", start);
  // Outputs: each through a temporary file; the report last, so a report means a result.
  writeSolution(o.output, scene, solution);
  printOutcome(solve, solution, o.output);
  Json report = solveReport(scene, solve, solution);
  addMeasures(report, o, measures, scene, solve, solution);
  report["history"] = history;
  stages.add("writing", start);
  report["stages"] = stagesTable(stages);
  if (!o.report.empty())
    writeFileAtomically(o.report, [&](std::ostream& out) { out << report.dump(2) << "\n"; });
}

/// When shooting stops, and how hard it shoots.
void addStopFlags(CLI::App& sub, SolverBlock& flags) {
  sub.add_option("--tolerance", flags.tolerance,
                 "Stop when unshot/emitted power falls below this (solver.tolerance; default 1e-3; as the final "
                 "gather's start 1e-2 or a tenth of a shot per patch, whichever comes first)")
      ->check(CLI::Range(1e-300, 1.0));
  sub.add_option("--max-shots", flags.maxShots, "Stop after this many shots (solver.max_shots)")
      ->check(CLI::PositiveNumber);
  sub.add_option("--time-limit", flags.timeLimit, "Stop after this many seconds (solver.time_limit)")
      ->check(CLI::PositiveNumber);
  sub.add_option("--overshoot", flags.overshoot,
                 "Overshooting factor ω in [1, 2] (solver.overshoot; default 1.3, measured; 1: plain shooting)")
      ->check(CLI::Range(1.0, 2.0));
}

/// What the history measures: the true error against a reference, the distance to a fixed point.
void addMeasureFlags(CLI::App& sub, SolveOptions& o) {
  sub.add_option("--reference", o.reference,
                 "Measure the true error against a reference CSV from 'radiosity reference': the "
                 "report's history and its 'error' block then hold the relative error of what a "
                 "viewer shows at the reference's points");
  sub.add_option("--fixed-point", o.fixedPoint,
                 "Measure convergence (not error) to 'direct' (the full system solved from the same "
                 "hemicubes first; every patch then shoots alone, no clusters) or an earlier result PLY of the same scene and mesh settings: "
                 "the history's fixed_point_distance, relative L2 over elements");
}

}  // namespace

Command addSolveCommand(CLI::App& app) {
  Subcommand<SolveOptions> c(app, "solve",
                             "Solve the scene by progressive refinement and write the result mesh (vertex "
                             "radiosities as colours) and, optionally, a JSON report");
  addSceneAndOutput(*c.app, c.o->scene, c.o->output, "Result mesh (binary PLY)");
  c.app->add_option("--report", c.o->report, "Report file (JSON): settings, counts, energy ledger, history");
  addMeshFlags(*c.app, c.o->flags);
  addSolverFlags(*c.app, c.o->flags);
  addStopFlags(*c.app, c.o->flags);
  addMeasureFlags(*c.app, *c.o);
  c.app->add_option("--exposure", c.o->flags.exposure,
                  "Display exposure K (solver.exposure; default: automatic, see README)")
      ->check(CLI::PositiveNumber);
  return c.runs(runSolve);
}

}  // namespace rad::cli
