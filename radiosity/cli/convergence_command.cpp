// radiosity convergence SCENE --reference REFERENCE.csv -o PLOT.svg [--csv DATA.csv]: the true
// error (against an independent reference) against run time, for the solver variants on one
// mesh and for a ladder of settings solved the way `radiosity solve` solves, with the front of
// the fastest setting for each error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>

#include <glm/common.hpp>

#include "mesh/base/error.h"
#include "mesh/base/output_file.h"
#include "mesh/patch_mesh.h"
#include "mesh/results/reference_points.h"
#include "radiosity/cli/commands.h"
#include "radiosity/cli/svg_plot.h"
#include "radiosity/reference_solver.h"
#include "radiosity/result.h"
#include "radiosity/settings.h"
#include "radiosity/shooting/progressive_solver.h"
#include "radiosity/true_error.h"

namespace rad::cli {
namespace {

constexpr int kMaxSweeps = 200;
/// Progressive runs stop at this many shots per patch at most, or at this share unshot.
constexpr long kMaxShotsPerPatch = 40;
constexpr double kVariantTolerance = 1e-5;
/// The ladder's solves stop at this share unshot (ten times below the default tolerance, so
/// that each curve shows where its discretisation levels off).
constexpr double kLadderTolerance = 1e-4;
/// History rows: at shot counts growing by this factor.
constexpr double kRowGrowth = 1.15;
/// Overshooting factor of the "overshooting" curve unless --overshoot says otherwise.
constexpr double kOvershootCurve = 1.3;

struct ConvergenceOptions {
  std::string scene, output, csv, reference;
  SolverBlock flags;
  bool variants = true, ladder = true;
};

struct Curve {
  Series series;
  std::vector<long> steps;  ///< shots or sweeps

  /// An empty curve called `name`.
  explicit Curve(std::string name) : series{std::move(name), {}} {}

  /// One history row: the time, the error and the shots or sweeps so far.
  void add(double seconds, double error, long step) {
    series.points.push_back({seconds, error});
    steps.push_back(step);
  }
};

/// Whether a run at `shots` is due for a history row; moves `next` on when it is.
bool rowDue(long shots, long& next) {
  if (shots < next) return false;
  next = std::max(next + 1, long(next * kRowGrowth));
  return true;
}

/// The emission of every element: the gathering sweeps' start.
std::vector<glm::dvec3> emissionOf(const PatchMesh& mesh) {
  std::vector<glm::dvec3> E(mesh.elementCount());
  for (int e = 0; e < mesh.elementCount(); ++e) E[e] = mesh.emission(e);
  return E;
}

/// Seconds from `since` to now.
double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// The scene meshed by the flags without the mesher's warnings: the commands meshes it many
/// times.
MeshedScene meshQuietly(Scene scene, const SolverBlock& flags) {
  const Settings settings = resolveSettings(scene, flags);
  return meshScene(std::move(scene), settings);
}

/// The true error of what the solver shows now; `ambient` shows B + ρ·ambient.
double shownError(const ProgressiveSolver& solver, const PatchMesh& mesh, bool ambient, const TrueError& truth) {
  const glm::dvec3 a = ambient ? glm::max(solver.ambient(), glm::dvec3(0.0)) : glm::dvec3(0.0);
  return truth.measure(shownVertexRadiosity(mesh, solver.radiosity(), a, nullptr)).rms;
}

/// The options of a variant's progressive run: the user's, stopped at kVariantTolerance (or
/// theirs if lower) or kMaxShotsPerPatch shots per patch.
SolverOptions variantOptions(SolverOptions options, const PatchMesh& mesh) {
  options.tolerance = std::min(options.tolerance, kVariantTolerance);
  options.clusters = false;  // the very factors Jacobi and Gauss-Seidel iterate
  options.followingResolution = 0;
  options.maxShots = kMaxShotsPerPatch * long(mesh.patches.size());
  return options;
}

/// One progressive run on fixed factors; `ambient` shows B + ρ·ambient.
Curve progressiveCurve(const std::string& name, const PatchMesh& mesh, FactorSource& factors,
                       const SolverOptions& options, bool ambient, const TrueError& truth) {
  Curve c(name);
  ProgressiveSolver solver(mesh, factors, variantOptions(options, mesh));
  long next = 1;
  c.add(0, shownError(solver, mesh, ambient, truth), 0);
  while (solver.step())
    if (rowDue(solver.shots(), next))  // the solver's own time: measuring is not in it
      c.add(solver.seconds(), shownError(solver, mesh, ambient, truth), solver.shots());
  return c;
}

/// A gathering solve's sweeps as rows of a curve, its clock stopped while it measures; it
/// stops the solve once the error settles.
struct SweepRecorder {
  Curve& c;
  const PatchMesh& mesh;
  const TrueError& truth;
  double start;  ///< the time the matrix took to build
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  double measuring = 0, last = HUGE_VAL;

  /// Records sweep `sweep` (radiosities B); false once the error has settled.
  bool operator()(int sweep, const std::vector<glm::dvec3>& B) {
    auto m0 = std::chrono::steady_clock::now();
    const double e = truth.measure(vertexRadiosity(mesh, B)).rms;
    c.add(start + seconds(t0) - measuring, e, sweep);
    measuring += seconds(m0);
    const bool settled = std::abs(e - last) < 1e-5 * e;
    last = e;
    return !settled;
  }
};

/// Jacobi or Gauss–Seidel, starting at the time the matrix took to build.
Curve gatheringCurve(const std::string& name, const TransportMatrix& system, double start,
                     bool gaussSeidel, const PatchMesh& mesh, const TrueError& truth) {
  Curve c(name);
  c.add(start, truth.measure(vertexRadiosity(mesh, emissionOf(mesh))).rms, 0);
  SweepRecorder record{c, mesh, truth, start};
  if (gaussSeidel) system.solveGaussSeidel(kMaxSweeps, std::ref(record));
  else system.solveJacobi(kMaxSweeps, std::ref(record));
  return c;
}

/// The flags of the variants' one uniform mesh: the user's, without refinement, vertex direct
/// light or the final gather (the variants are the solvers of element radiosities).
SolverBlock uniformFlags(SolverBlock flags) {
  flags.adaptive = false;
  flags.vertexDirect = false;
  flags.finalGather = false;
  return flags;
}

/// The name of the overshooting curve, with its ω.
std::string overshootingName(double overshoot) {
  char name[80];
  std::snprintf(name, sizeof name, "overshooting w=%.2g", overshoot);
  return name;
}

/// Plain, ambient and overshooting progressive refinement on the factors.
std::vector<Curve> progressiveCurves(const ConvergenceOptions& o, const PatchMesh& mesh, FactorSource& factors,
                                     SolverOptions options, const TrueError& truth) {
  SolverOptions overshooting = options;
  overshooting.overshoot = o.flags.overshoot.value_or(kOvershootCurve);
  options.overshoot = 1;  // the plain curves shoot plainly, whatever the settings say
  const std::string name = overshootingName(overshooting.overshoot);
  return {progressiveCurve("progressive", mesh, factors, options, false, truth),
          progressiveCurve("progressive + ambient", mesh, factors, options, true, truth),
          progressiveCurve(name, mesh, factors, overshooting, false, truth)};
}

/// Plain, ambient and overshooting progressive refinement, Jacobi and Gauss–Seidel on one
/// uniform mesh's factors, one thread each; element values shown through vertexRadiosity.
std::vector<Curve> variantCurves(const ConvergenceOptions& o, Scene scene, const std::vector<ReferencePoint>& points) {
  const MeshedScene meshed = meshQuietly(std::move(scene), uniformFlags(o.flags));
  const PatchMesh& mesh = meshed.mesh;
  const TrueError truth(mesh, meshed.scene, points, o.reference);
  const SolverOptions options = solverOptions(meshed);
  std::unique_ptr<HemicubeFactors> factors = hemicubeFactors(meshed, 1);
  auto t0 = std::chrono::steady_clock::now();
  TransportMatrix system(mesh, *factors, options);
  const double matrixSeconds = seconds(t0);
  std::vector<Curve> curves = progressiveCurves(o, mesh, *factors, options, truth);
  curves.push_back(gatheringCurve("Jacobi", system, matrixSeconds, false, mesh, truth));
  curves.push_back(gatheringCurve("Gauss-Seidel", system, matrixSeconds, true, mesh, truth));
  std::fprintf(stderr, "radiosity: variants on %d uniform elements (one thread; matrix %.2f s)\n",
               mesh.elementCount(), matrixSeconds);
  return curves;
}

/// A rung of the accuracy ladder: a name and the flags it changes from the user's.
struct Rung {
  std::string name;
  SolverBlock flags;
};

/// The rung `name`: the user's flags with `change` applied.
template <class Change>
Rung rung(const std::string& name, const SolverBlock& user, Change change) {
  Rung r{name, user};
  change(r.flags);
  return r;
}

/// The ladder's rungs: the defaults, then one setting each made coarser or finer.
std::vector<Rung> ladder(const SolverBlock& user, const Scene& scene) {
  const Settings defaults = resolveSettings(scene, user);
  const double edge = defaults.maxElementEdge;
  return {rung("defaults", user, [](SolverBlock&) {}),
          rung("final gather off", user, [](SolverBlock& f) { f.finalGather = false; }),
          rung("gather R/2", user, [&](SolverBlock& f) { f.gatherResolution = defaults.gatherResolution / 2; }),
          rung("gather Rx2", user, [&](SolverBlock& f) { f.gatherResolution = defaults.gatherResolution * 2; }),
          rung("adaptive off", user, [](SolverBlock& f) { f.adaptive = false; }),
          rung("elements x1.6", user, [&](SolverBlock& f) { f.maxElementEdge = edge * 1.6; }),
          rung("elements /1.6", user, [&](SolverBlock& f) { f.maxElementEdge = edge / 1.6; }),
          rung("hemicube R/2", user, [&](SolverBlock& f) { f.hemicubeResolution = defaults.shooting(defaults.finalGather).hemicubeResolution / 2; }),
          rung("hemicube Rx2", user, [&](SolverBlock& f) { f.hemicubeResolution = defaults.shooting(defaults.finalGather).hemicubeResolution * 2; }),
          rung("4 points per patch", user, [&](SolverBlock& f) { f.shooterSamples = 4 * defaults.shooterSamples; }),
          rung("emitter points /4", user,
               [&](SolverBlock& f) { f.emitterSamples = std::max(1, defaults.emitterSamples / 4); })};
}

/// The rung's line on stderr: its mesh, its times and its final true error.
void printRung(const Rung& rung, const MeshedScene& meshed, double meshing, const Curve& c) {
  std::fprintf(stderr, "  %-20s %6d elements, meshing %.2f s, %.2f s in all, true error %.2f %%\n",
               rung.name.c_str(), meshed.mesh.elementCount(), meshing, c.series.points.back().first,
               100 * c.series.points.back().second);
}

/// The final gather's point: at the time the solve and the gather took together.
void addGathered(Curve& c, const RadiositySolve& solve, const MeshedScene& meshed, const TrueError& truth,
                 double meshing) {
  const Solution gathered = solve.bake();
  const double seconds = gathered.gather.hemicubeSeconds + gathered.gather.solveSeconds;
  c.add(meshing + solve.solver().seconds() + seconds, truth.measure(shownAtVertices(meshed, gathered)).rms,
        solve.solver().shots());
}

/// The rung's flags, stopped at kLadderTolerance unless the user gave a tolerance; a rung that
/// gathers stops its progressive start as `radiosity solve` does (the gather converges from it).
SolverBlock ladderFlags(const Rung& rung, const Scene& scene) {
  SolverBlock flags = rung.flags;
  if (!flags.tolerance && !resolveSettings(scene, flags).finalGather) flags.tolerance = kLadderTolerance;
  return flags;
}

/// Runs the solve to its end, the error of what a viewer shows added to c at each history
/// row and at the end, its time counted from `meshing` seconds.
void solveRecording(RadiositySolve& solve, const MeshedScene& meshed, const TrueError& truth, double meshing,
                    Curve& c) {
  const ProgressiveSolver& solver = solve.solver();
  auto record = [&] { c.add(meshing + solver.seconds(), trueErrorNow(solve, meshed, truth).rms, solver.shots()); };
  long next = 1;
  while (solve.step())
    if (rowDue(solver.shots(), next)) record();
  record();
  if (meshed.gather.on) addGathered(c, solve, meshed, truth, meshing);
}

/// A rung solved as `radiosity solve` solves (all workers), its time counting meshing, rays
/// and refinement; the error of what a viewer shows at each history row.
Curve ladderCurve(const Rung& rung, const Scene& scene, const std::vector<ReferencePoint>& points,
                  const std::string& reference) {
  Curve c(rung.name);
  auto t0 = std::chrono::steady_clock::now();
  const MeshedScene meshed = meshQuietly(scene, ladderFlags(rung, scene));
  const double meshing = seconds(t0);
  const TrueError truth(meshed.mesh, meshed.scene, points, reference);
  RadiositySolve solve(meshed);
  solveRecording(solve, meshed, truth, meshing, c);
  printRung(rung, meshed, meshing, c);
  return c;
}

/// Every point of every curve, by time (then error).
std::vector<std::pair<double, double>> pointsByTime(const std::vector<Curve>& curves) {
  std::vector<std::pair<double, double>> all;
  for (const auto& c : curves) all.insert(all.end(), c.series.points.begin(), c.series.points.end());
  std::sort(all.begin(), all.end());
  return all;
}

/// The lowest error reached by any ladder curve by each time: the fastest setting per error.
Curve front(const std::vector<Curve>& curves) {
  Curve f("front (ladder)");
  double best = HUGE_VAL;
  for (const auto& [t, e] : pointsByTime(curves))
    if (e < best) best = e, f.add(t, e, 0);
  return f;
}

using Curves = std::vector<std::pair<std::string, Curve>>;  // (group, curve)

/// The ladder's curves and their front.
void addLadder(Curves& curves, const ConvergenceOptions& o, const Scene& scene,
               const std::vector<ReferencePoint>& points) {
  std::fprintf(stderr, "radiosity: accuracy ladder (as 'radiosity solve' runs, to unshot %g)\n", kLadderTolerance);
  std::vector<Curve> rungs;
  for (const Rung& r : ladder(o.flags, scene)) rungs.push_back(ladderCurve(r, scene, points, o.reference));
  Curve f = front(rungs);
  for (auto& c : rungs) curves.push_back({"ladder", std::move(c)});
  curves.push_back({"front", std::move(f)});
}

/// The curve's rows of the CSV, one per history row.
void writeCsvRows(std::ostream& csv, const std::string& group, const Curve& c) {
  for (size_t i = 0; i < c.steps.size(); ++i)
    csv << group << "," << c.series.name << "," << c.series.points[i].first << "," << c.steps[i] << ","
        << c.series.points[i].second << "\n";
}

/// The data as CSV: group,name,seconds,steps,error.
std::string csvOf(const Curves& curves) {
  std::ostringstream csv;
  csv << "group,name,seconds,steps,error\n";
  for (const auto& [group, c] : curves) writeCsvRows(csv, group, c);
  return csv.str();
}

/// The curves as plot series, the ladder's names marked as such.
std::vector<Series> plotSeries(const Curves& curves) {
  std::vector<Series> series;
  for (const auto& [group, c] : curves) {
    series.push_back(c.series);
    series.back().name = (group == "ladder" ? "ladder: " : "") + c.series.name;
  }
  return series;
}

/// The plot of every curve as SVG, titled with the reference file.
std::string svgOf(const Curves& curves, const std::string& reference) {
  const std::vector<Series> series = plotSeries(curves);
  return svgLogPlot("True error (RMS relative, vs " + reference + ") against run time", "seconds", "true error",
                    series);
}

/// Each curve's last true error, time and step count on stderr.
void printSummary(const Curves& curves) {
  for (const auto& [group, c] : curves)
    std::fprintf(stderr, "  %-7s %-24s true error %.2f %% after %.2f s (%ld steps)\n", group.c_str(),
                 c.series.name.c_str(), 100 * c.series.points.back().second, c.series.points.back().first,
                 c.steps.back());
}

/// Every curve the options ask for: the variants, then the ladder and its front.
Curves allCurves(const ConvergenceOptions& o, const Scene& scene, const std::vector<ReferencePoint>& points) {
  Curves curves;
  if (o.variants)
    for (auto& c : variantCurves(o, scene, points)) curves.push_back({"variant", std::move(c)});
  if (o.ladder) addLadder(curves, o, scene, points);
  return curves;
}

/// Writes the plot and, when asked for, the CSV.
void writeOutputs(const ConvergenceOptions& o, const Curves& curves) {
  const std::string svg = svgOf(curves, o.reference);
  writeFileAtomically(o.output, [&](std::ostream& out) { out << svg; });
  if (!o.csv.empty()) writeFileAtomically(o.csv, [&](std::ostream& out) { out << csvOf(curves); });
}

void runConvergence(const ConvergenceOptions& o) {
  checkOutputPath(o.output);
  if (!o.csv.empty()) checkOutputPath(o.csv);
  const std::vector<ReferencePoint> points = readReferenceFile(o.reference).points;
  Scene scene = loadSceneToSolve(o.scene);
  printWarnings(scene.warnings);
  const Curves curves = allCurves(o, scene, points);
  writeOutputs(o, curves);
  printSummary(curves);
}

/// The command's own flags: what to run and the stopping and overshooting of its curves.
void addCurveFlags(CLI::App& sub, ConvergenceOptions& o) {
  sub.add_option("--reference", o.reference, "Reference CSV from 'radiosity reference' for this scene")->required();
  sub.add_option("--csv", o.csv, "The data: group,name,seconds,steps,error");
  sub.add_option("--tolerance", o.flags.tolerance,
                 "The ladder's solves stop when unshot/emitted power falls below this (default 1e-4)")
      ->check(CLI::Range(1e-300, 1.0));
  sub.add_option("--overshoot", o.flags.overshoot, "ω of the overshooting curve (default 1.3)")
      ->check(CLI::Range(1.0, 2.0));
  sub.add_option("--variants", o.variants, "Run the solver variants on one mesh, true or false (default true)");
  sub.add_option("--ladder", o.ladder, "Run the accuracy ladder of settings, true or false (default true)");
}

}  // namespace

Command addConvergenceCommand(CLI::App& app) {
  Subcommand<ConvergenceOptions> c(app, "convergence",
                                   "Plot the true error (against a reference from 'radiosity reference') against run "
                                   "time (SVG, and CSV): progressive refinement, with the ambient term, with "
                                   "overshooting, Jacobi and Gauss-Seidel on one uniform mesh, and a ladder of "
                                   "settings solved as 'radiosity solve' does, with its front");
  addSceneAndOutput(*c.app, c.o->scene, c.o->output, "Plot (SVG)");
  addCurveFlags(*c.app, *c.o);
  addMeshFlags(*c.app, c.o->flags);
  addSolverFlags(*c.app, c.o->flags);
  return c.runs(runConvergence);
}

}  // namespace rad::cli
