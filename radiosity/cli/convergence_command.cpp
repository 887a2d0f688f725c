// radiosity convergence SCENE -o PLOT.svg [--csv DATA.csv]: error against run time for plain
// progressive refinement, progressive with the ambient term, overshooting, Jacobi and
// Gauss–Seidel, all on the same hemicube factors, against the direct solution.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "mesh/error.h"
#include "mesh/output_file.h"
#include "mesh/patch_mesh.h"
#include "mesh/settings.h"
#include "radiosity/cli/commands.h"
#include "radiosity/cli/svg_plot.h"
#include "radiosity/progressive_solver.h"
#include "radiosity/reference_solver.h"

namespace rad::cli {
namespace {

/// Each method runs until its error falls below this, or its budget runs out.
constexpr double kTargetError = 1e-4;
constexpr int kMaxSweeps = 200;
/// Progressive runs stop at this many shots per patch at most.
constexpr long kMaxShotsPerPatch = 40;
/// Overshooting factor of the "overshooting" curve unless --overshoot says otherwise.
constexpr double kOvershootCurve = 1.3;

struct ConvergenceOptions {
  std::string scene, output, csv;
  SolverBlock flags;
};

struct Curve {
  Series series;
  std::vector<long> steps;  ///< shots or sweeps
};

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// One progressive run; `ambient` measures the displayed solution B + ρ·ambient.
Curve progressiveCurve(const std::string& name, const PatchMesh& mesh, FactorSource& factors,
                       SolverOptions options, bool ambient, const std::vector<glm::dvec3>& reference) {
  Curve c{{name, {}}, {}};
  options.tolerance = 1e-12;
  options.maxShots = kMaxShotsPerPatch * long(mesh.patches.size());
  ProgressiveSolver solver(mesh, factors, options);
  std::vector<glm::dvec3> shown(mesh.elementCount());
  auto error = [&] {
    if (!ambient) return relativeError(mesh, solver.radiosity(), reference);
    glm::dvec3 a = solver.ambient();
    for (int e = 0; e < mesh.elementCount(); ++e) shown[e] = solver.radiosity()[e] + mesh.reflectance(e) * a;
    return relativeError(mesh, shown, reference);
  };
  double measuring = 0;  // the error evaluations are not the solver's time
  long next = 1;
  c.series.points.push_back({0, error()});
  c.steps.push_back(0);
  while (solver.step()) {
    if (solver.shots() < next) continue;
    next = std::max(next + 1, long(next * 1.1));
    auto t0 = std::chrono::steady_clock::now();
    double e = error();
    c.series.points.push_back({solver.seconds() - measuring, e});
    c.steps.push_back(solver.shots());
    measuring += seconds(t0);
    if (e < kTargetError) break;
  }
  return c;
}

/// Jacobi or Gauss–Seidel, starting at the time the matrix took to build.
Curve gatheringCurve(const std::string& name, const TransportMatrix& system, double start,
                     bool gaussSeidel, const PatchMesh& mesh, const std::vector<glm::dvec3>& reference) {
  Curve c{{name, {}}, {}};
  std::vector<glm::dvec3> E(mesh.elementCount());
  for (int e = 0; e < mesh.elementCount(); ++e) E[e] = mesh.emission(e);
  c.series.points.push_back({start, relativeError(mesh, E, reference)});
  c.steps.push_back(0);
  double measuring = 0;
  auto t0 = std::chrono::steady_clock::now();
  auto record = [&](int sweep, const std::vector<glm::dvec3>& B) {
    auto m0 = std::chrono::steady_clock::now();
    double e = relativeError(mesh, B, reference);
    c.series.points.push_back({start + seconds(t0) - measuring, e});
    c.steps.push_back(sweep);
    measuring += seconds(m0);
    return e >= kTargetError;
  };
  if (gaussSeidel) system.solveGaussSeidel(kMaxSweeps, record);
  else system.solveJacobi(kMaxSweeps, record);
  return c;
}

void runConvergence(const ConvergenceOptions& o) {
  checkOutputPath(o.output);
  if (!o.csv.empty()) checkOutputPath(o.csv);
  // The solvers are compared on one mesh against its dense direct solution: adaptive
  // refinement would only multiply the elements (up to 8 000 fit), so it is off unless asked;
  // element values are compared, so no direct light is cast to the vertices.
  SolverBlock flags = o.flags;
  if (!flags.adaptive) flags.adaptive = false;
  flags.vertexDirect = false;
  SolvableScene solvable = loadSolvable(o.scene, flags);
  const auto& [scene, settings, mesh, direct, adaptive, base] = solvable;
  SolverOptions options = solverOptions(settings);
  // One worker, so that every method's time is single-threaded and comparable.
  std::unique_ptr<HemicubeFactors> hemicubes = hemicubeFactors(solvable, 1);
  HemicubeFactors& factors = *hemicubes;

  auto t0 = std::chrono::steady_clock::now();
  TransportMatrix system(mesh, factors, options);
  double matrixSeconds = seconds(t0);
  std::vector<glm::dvec3> reference = system.solveDirect();
  std::fprintf(stderr, "radiosity: %d elements, %zu patches; matrix %.2f s, direct solve %.2f s\n",
               mesh.elementCount(), mesh.patches.size(), matrixSeconds, seconds(t0) - matrixSeconds);

  SolverOptions overshooting = options;
  overshooting.overshoot = o.flags.overshoot.value_or(kOvershootCurve);
  options.overshoot = 1;  // the plain curves shoot plainly, whatever the settings say
  std::vector<Curve> curves;
  curves.push_back(progressiveCurve("progressive", mesh, factors, options, false, reference));
  curves.push_back(progressiveCurve("progressive + ambient", mesh, factors, options, true, reference));
  char name[64];
  std::snprintf(name, sizeof name, "overshooting w=%.2g", overshooting.overshoot);
  curves.push_back(progressiveCurve(name, mesh, factors, overshooting, false, reference));
  curves.push_back(gatheringCurve("Jacobi", system, matrixSeconds, false, mesh, reference));
  curves.push_back(gatheringCurve("Gauss-Seidel", system, matrixSeconds, true, mesh, reference));

  std::vector<Series> series;
  std::ostringstream csv;
  csv << "method,seconds,steps,error\n";
  for (const auto& c : curves) {
    series.push_back(c.series);
    for (size_t i = 0; i < c.steps.size(); ++i)
      csv << c.series.name << "," << c.series.points[i].first << "," << c.steps[i] << ","
          << c.series.points[i].second << "\n";
  }
  std::ostringstream title;
  title << "Relative L2 error vs time, " << mesh.elementCount() << " elements";
  std::string svg = svgLogPlot(title.str(), "seconds", "relative L2 error", series);
  writeFileAtomically(o.output, [&](std::ostream& out) { out << svg; });
  if (!o.csv.empty()) writeFileAtomically(o.csv, [&](std::ostream& out) { out << csv.str(); });
  for (const auto& c : curves)
    std::fprintf(stderr, "  %-24s error %.2e after %.2f s (%ld steps)\n", c.series.name.c_str(),
                 c.series.points.back().second, c.series.points.back().first, c.steps.back());
}

}  // namespace

Command addConvergenceCommand(CLI::App& app) {
  auto o = std::make_shared<ConvergenceOptions>();
  CLI::App* sub = app.add_subcommand(
      "convergence", "Plot relative L2 error against run time (SVG, and CSV) for progressive "
                     "refinement, with the ambient term, with overshooting, Jacobi and Gauss-Seidel "
                     "on the same hemicube factors, against the direct solution");
  sub->add_option("scene", o->scene, "Scene file (JSON, version 1)")->required();
  sub->add_option("-o,--output", o->output, "Plot (SVG)")->required();
  sub->add_option("--csv", o->csv, "The data: method,seconds,steps,error");
  sub->add_option("--overshoot", o->flags.overshoot, "ω of the overshooting curve (default 1.3)")
      ->check(CLI::Range(1.0, 2.0));
  addMeshFlags(*sub, o->flags);
  addSolverFlags(*sub, o->flags);
  return {sub, [o] { runConvergence(*o); }};
}

}  // namespace rad::cli
