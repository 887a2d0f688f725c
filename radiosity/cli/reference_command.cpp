// radiosity reference SCENE -o REFERENCE.csv: radiosity at surface points by path tracing,
// independent of the hemicube solver, to measure the solver's true error against.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include <glm/geometric.hpp>
#include <unistd.h>

#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/base/number_text.h"
#include "mesh/base/output_file.h"
#include "mesh/facing.h"
#include "mesh/results/reference_points.h"
#include "radiosity/cli/commands.h"
#include "radiosity/pathtrace/path_tracer.h"

namespace rad::cli {
namespace {

/// A point of --points must lie this close (share of the scene's size) to a surface.
constexpr double kPointTolerance = 1e-3;
constexpr int kDefaultCount = 300;

struct ReferenceOptions {
  std::string scene, output, points;
  int count = kDefaultCount;
  long paths = 0, minPaths = pathtrace::kDefaultMinPaths, maxPaths = pathtrace::kDefaultMaxPaths;
  double relativeError = 0.01;
  unsigned seed = 1;
  std::optional<bool> fixFacing;
};

/// One line's point: six finite numbers (position, non-zero normal) and an optional tag.
pathtrace::SurfacePoint parsePoint(std::istringstream& words, const std::string& line, const std::string& where) {
  double v[6];
  for (double& x : v)
    if (!(words >> x) || !std::isfinite(x)) throw inputError(where, "x y z nx ny nz [tag], six finite numbers", "'" + line + "'");
  pathtrace::SurfacePoint p{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, -1, "point"};
  words >> p.tag;
  if (!(glm::length(p.normal) > 0)) throw inputError(where, "a non-zero normal", "(0, 0, 0)");
  return p;
}

/// Finds the point's surface, or refuses a point on none.
void locateOrRefuse(const pathtrace::TraceScene& scene, pathtrace::SurfacePoint& p, const std::string& where) {
  if (!pathtrace::locatePoint(scene, p, kPointTolerance * scene.size()))
    throw inputError(where, "a point on a surface, within " + std::to_string(kPointTolerance) +
                                " of the scene's size along its normal, on the side the normal faces",
                     "none there");
}

/// Whether the line holds anything but blanks.
bool hasWords(const std::string& line) {
  std::istringstream words(line);
  std::string first;
  return bool(words >> first);
}

/// The point of one line (`where` names it in errors), on its surface.
pathtrace::SurfacePoint pointOfLine(const pathtrace::TraceScene& scene, const std::string& line, const std::string& where) {
  std::istringstream words(line);
  pathtrace::SurfacePoint p = parsePoint(words, line, where);
  locateOrRefuse(scene, p, where);
  return p;
}

/// Reads `x y z nx ny nz [tag]` lines ('#' starts a comment) and finds each point's surface.
std::vector<pathtrace::SurfacePoint> readPoints(const std::string& path, const pathtrace::TraceScene& scene) {
  std::istringstream in(readInputFile(path, "a readable points file"));
  std::vector<pathtrace::SurfacePoint> out;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    line = line.substr(0, line.find('#'));
    if (hasWords(line)) out.push_back(pointOfLine(scene, line, path + ": line " + std::to_string(lineNo)));
  }
  if (out.empty()) throw inputError(path, "at least one point", "none");
  return out;
}

/// A progress bar of the share done, redrawn in place on stderr.
void showProgress(double share) {
  const int width = 40, filled = int(share * width);
  std::fprintf(stderr, "\rradiosity reference [%s%s] %3.0f%%", std::string(size_t(filled), '#').c_str(),
               std::string(size_t(width - filled), '.').c_str(), 100 * share);
}

/// The points to measure: from --points, or placed.
std::vector<pathtrace::SurfacePoint> pointsFor(const ReferenceOptions& o, const Scene& scene,
                                               const pathtrace::TraceScene& traced) {
  std::vector<pathtrace::SurfacePoint> points =
      o.points.empty() ? pathtrace::placePoints(traced, o.count, o.seed) : readPoints(o.points, traced);
  if (points.empty()) throw inputError(scene.path, "a non-emitting surface to place points on", "none");
  return points;
}

/// The path tracer's options from the command's.
pathtrace::TraceOptions traceOptions(const ReferenceOptions& o) {
  // seed, paths, relative error, fewest and most paths (never below the fewest), every
  // hardware thread, no progress
  return {o.seed, o.paths, o.relativeError, o.minPaths, std::max(o.maxPaths, o.minPaths), 0, nullptr};
}

/// How the estimates came out: the fewest and most paths per point, and the points that
/// stopped at the cap before reaching the relative error.
struct PathCounts {
  long capped = 0, fewest = 0, most = 0;

  /// Counts one point's estimate; `capping`: it stopped at maxPaths if it has that many.
  void add(const pathtrace::PointEstimate& e, bool capping, long maxPaths) {
    capped += capping && e.paths >= maxPaths;
    fewest = std::min(fewest, e.paths);
    most = std::max(most, e.paths);
  }
};

/// A point of the reference file: where, its surface's name, its tag and the estimate.
ReferencePoint referencePoint(const Scene& scene, const pathtrace::SurfacePoint& p, const pathtrace::PointEstimate& e) {
  return {p.position, p.normal, scene.surfaces[size_t(p.surface)].name, p.tag, e.B, e.standardError, e.paths};
}

/// The reference file's points, and the path counts.
ReferenceFile referencePoints(const Scene& scene, const std::vector<pathtrace::SurfacePoint>& points,
                              const std::vector<pathtrace::PointEstimate>& estimates, bool capping,
                              long maxPaths, PathCounts& counts) {
  ReferenceFile file;
  counts = {0, estimates[0].paths, 0};
  for (size_t i = 0; i < points.size(); ++i) {
    file.points.push_back(referencePoint(scene, points[i], estimates[i]));
    counts.add(estimates[i], capping, maxPaths);
  }
  return file;
}

/// The header's paths-per-point line: the fixed count, or the relative error, bounds and capped points.
std::string pathsPerPointLine(const ReferenceOptions& o, const pathtrace::TraceOptions& options,
                              const PathCounts& counts) {
  if (o.paths > 0) return formatted("paths per point: %ld", o.paths);
  return formatted("paths per point: until SE/B < %g in every channel (%ld to %ld; %ld points stopped at the cap)",
                   o.relativeError, options.minPaths, options.maxPaths, counts.capped);
}

/// The header's points line: how many, and placed how or read from where.
std::string pointsLine(const ReferenceOptions& o, size_t points) {
  return "points: " + std::to_string(points) +
         (o.points.empty() ? " placed (3/4 by area, 1/8 near edges, 1/8 near contact lines)" : " from " + o.points);
}

/// The header lines: method, scene, seed, points, paths and time.
std::vector<std::string> referenceHeader(const ReferenceOptions& o, const pathtrace::TraceOptions& options,
                                         const Scene& scene, size_t points, const PathCounts& counts,
                                         long traced, double seconds) {
  return {"radiosity reference: path tracing (next-event estimation and cosine-weighted bounces "
          "combined by the power heuristic, Russian roulette), independent of the hemicube solver",
          "scene: " + scene.path,
          "seed: " + std::to_string(o.seed),
          pointsLine(o, points),
          pathsPerPointLine(o, options, counts),
          formatted("paths: %ld (%ld to %ld per point)", traced, counts.fewest, counts.most),
          formatted("seconds: %.3f (%.3g paths per second)", seconds, double(traced) / seconds)};
}

/// The closing line: points, paths, time and rate, and the file written.
void printWritten(size_t points, long paths, double seconds, const std::string& output) {
  std::fprintf(stderr, "radiosity: %zu points, %ld paths in %.2f s (%.3g per second); wrote %s\n", points, paths,
               seconds, double(paths) / seconds, output.c_str());
}

/// The estimates at the points, with a progress bar when stderr is a terminal; `seconds`:
/// the time they took.
std::vector<pathtrace::PointEstimate> traceTimed(const pathtrace::PathTracer& tracer,
                                                 const std::vector<pathtrace::SurfacePoint>& points,
                                                 pathtrace::TraceOptions options, double& seconds) {
  const bool terminal = isatty(STDERR_FILENO);
  if (terminal) options.progress = showProgress;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<pathtrace::PointEstimate> estimates = tracer.estimate(points, options);
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (terminal) std::fprintf(stderr, "\n");
  return estimates;
}

/// Writes the reference file: the points with their estimates, under the header.
void writeReference(const ReferenceOptions& o, const pathtrace::TraceOptions& options, const Scene& scene,
                    const std::vector<pathtrace::SurfacePoint>& points,
                    const std::vector<pathtrace::PointEstimate>& estimates, long traced, double seconds) {
  PathCounts counts;
  ReferenceFile file = referencePoints(scene, points, estimates, o.paths <= 0, options.maxPaths, counts);
  file.header = referenceHeader(o, options, scene, points.size(), counts, traced, seconds);
  writeReferenceFile(o.output, file);
}

void runReference(const ReferenceOptions& o) {
  checkOutputPath(o.output);
  Scene scene = loadSceneToSolve(o.scene);
  printWarnings(scene.warnings);
  // The surfaces a solve would turn round, turned alike: the reference measures the same scene.
  if (o.fixFacing.value_or(scene.solver.fixFacing.value_or(true))) printWarnings(turnToLitSpace(scene).warnings);
  const pathtrace::TraceScene traced(scene);
  const std::vector<pathtrace::SurfacePoint> points = pointsFor(o, scene, traced);
  const pathtrace::TraceOptions options = traceOptions(o);
  const pathtrace::PathTracer tracer(traced);
  double seconds = 0;
  const std::vector<pathtrace::PointEstimate> estimates = traceTimed(tracer, points, options, seconds);
  writeReference(o, options, scene, points, estimates, tracer.pathsTraced(), seconds);
  printWritten(points.size(), tracer.pathsTraced(), seconds, o.output);
}

/// --points or --count: the points to measure.
void addPointFlags(CLI::App& sub, ReferenceOptions& o) {
  auto* points = sub.add_option("--points", o.points, "Points to measure: lines 'x y z nx ny nz [tag]'");
  sub.add_option("--count", o.count, "Points to place when --points is not given (default 300)")
      ->check(CLI::Range(1, 1'000'000))
      ->excludes(points);
}

/// --paths or --relative-error with its bounds: how many paths each point takes.
void addPathFlags(CLI::App& sub, ReferenceOptions& o) {
  auto* paths = sub.add_option("--paths", o.paths, "Exactly this many paths per point")->check(CLI::Range(2L, 1L << 40));
  sub.add_option("--relative-error", o.relativeError,
                 "Trace each point until its standard error is below this share of B in every channel "
                 "(default 0.01)")
      ->check(CLI::Range(1e-6, 1.0))
      ->excludes(paths);
  sub.add_option("--min-paths", o.minPaths, "With --relative-error, at least this many paths per point (default 8192)")
      ->check(CLI::Range(2L, 1L << 40));
  sub.add_option("--max-paths", o.maxPaths, "With --relative-error, at most this many paths per point (default 2e7)")
      ->check(CLI::Range(2L, 1L << 40));
}

}  // namespace

Command addReferenceCommand(CLI::App& app) {
  Subcommand<ReferenceOptions> c(app, "reference",
                                 "Radiosity at surface points by Monte Carlo path tracing, independent of the "
                                 "hemicube solver, with standard errors (CSV): the truth to measure solves against");
  addSceneAndOutput(*c.app, c.o->scene, c.o->output, "Reference file (CSV)");
  addPointFlags(*c.app, *c.o);
  addPathFlags(*c.app, *c.o);
  c.app->add_option("--seed", c.o->seed, "Seed of the random streams (default 1)");
  c.app->add_option("--fix-facing", c.o->fixFacing,
                    "Turn round mesh-file surfaces that light meets mostly on their backs, as a solve does "
                    "(solver.fix_facing; default true)");
  return c.runs(runReference);
}

}  // namespace rad::cli
