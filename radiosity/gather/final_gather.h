#pragma once
// The final gather: the light shown at each display vertex, gathered at the vertex itself
// through its own hemicube over the solved elements, after the progressive solve.
//
// An element's solved radiosity is an average over the element that carries the shooters'
// proximity error, and a vertex reconstructed from its elements shows the light of the open
// surface beside an occluder. A point gather sees exactly what occludes the vertex (the block
// beside it hides half its sky) and has no proximity error. Gathering once over the solved
// elements would inherit part of their error, so the gather is iterated at the vertices (point
// collocation with linear elements): with x the light each vertex reflects,
//
//   x = d + ρ·F·W·x
//
// F the hemicube factors from each vertex to every element, W an element's value as the mean
// of its corners (the mean of the linear interpolant Gouraud shading shows), d the direct
// light at the vertex (by rays, when given; then an emitter's emission is not gathered again)
// or else ρ·F·E. Every row of a closed scene's F sums to 1, so a furnace comes out exact. The
// system is solved by BiCGSTAB from the progressive solution. The vertices of the mesh as built
// before refinement render hemicubes, but where that mesh is much finer than the scene's
// elements (a model's own faces) those near gathering ones take their light instead
// (radiosity/gather/gather_cache.h); so do the vertices refinement added, unless another
// surface is near (radiosity/gather/gather_points.h); every vertex's direct light is its own
// rays'.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <exception>
#include <future>
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"
#include "radiosity/gather/gather_cache.h"

namespace rad {

/// Hemicube resolution of the gather (pixels across the top face): on the Cornell box the
/// true error was 2.15 % at 16, 2.07 % at 32 and at 64 (0.38 / 0.49 / 0.6 s, drawing elements).
/// Drawing flat regions the cost follows the pixels, but 24 raises every true error
/// (CornellBox-Original 1.51 → 1.56 %, the Cornell box 1.56 → 1.64 %, near its blocks 3.83 →
/// 4.20 %, the doorway 1.95 → 2.16 %), so 32 stays.
constexpr int kDefaultGatherResolution = 32;
/// The gather is skipped (with a warning) when its hemicubes would take longer than this on
/// one core of this machine class (estimateGather): a quarter of an hour on two. Skipping it
/// costs more at scale, as the progressive solve then shoots at the full defaults (Modern Hall
/// split to 100k triangles, shot to 1e-3, took 11 minutes; gathered, its whole solve 80 s), so
/// the budget only keeps out a gather of hours.
constexpr double kMaxGatherSeconds = 1800;
/// The seconds one triangle a hemicube sorts to its faces costs on one core (CornellBox-Original
/// drawing its elements: 4 592 hemicubes over 7 690 elements in 0.52 s on two)...
constexpr double kGatherSecondsPerTriangle = 3e-8;
/// ...where the hemicubes cull hidden triangles, each drawn one costs more (the hierarchy's
/// visits and depth tests: Modern Hall split to 100k and 300k triangles, drawing elements,
/// 9.2e8 and 2.8e9 in 57 s and 198 s on two cores)...
constexpr double kCulledGatherSecondsPerTriangle = 1.3e-7;
/// ...and a pixel that shows a flat region's outline, resolved to its element (FlatRegions),
/// with the pixel's share of clearing and summing the faces: CornellBox-Original, 1.3e7 such
/// pixels in 0.55 s on two cores.
constexpr double kGatherSecondsPerLocatedPixel = 8e-8;
/// Gathering vertices whose hemicubes estimateGather renders to estimate the rest's.
constexpr int kGatherWorkProbes = 16;

struct GatherOptions {
  int resolution = kDefaultGatherResolution;
  unsigned seed = 1;
  /// Ward's accuracy for which vertices of the drawn mesh gather (GatherCache); 0: every one.
  double accuracy = kDefaultGatherAccuracy;
  /// A vertex the cache would interpolate gathers itself too where the gathering vertices it
  /// takes differ by more than this share of their mean over the progressive start's light,
  /// or it takes one alone; 0: never.
  double agreement = kDefaultGatherAgreement;
  /// The scene's element edge (0: the default's, the scene size / kDefaultElementsPerDiagonal):
  /// where the mesh is as fine as this, every vertex gathers (kGatherFarthestShare).
  double elementEdge = 0;
  int workers = 0;                ///< hemicubes rendering at once (0: one per hardware thread)
  double tolerance = 1e-5;        ///< relative residual of the vertex system
  int maxIterations = 200;
  /// Memory for the vertices' factors, kept to iterate; a scene that needs more is gathered
  /// once over the solved elements instead. 4 GiB: Modern Hall split to 1M triangles keeps
  /// about 3.4 GB (a vertex's row holds what its 32×32 hemicube shows, some 600 elements).
  size_t memoryBytes = size_t(4) << 30;
  /// A time limit: hemicubes not rendered by then are abandoned (the gather gives up) and the
  /// iteration stops where it is.
  std::optional<std::chrono::steady_clock::time_point> deadline;
};

struct GatherStats {
  int points = 0;        ///< vertices gathered at
  int ownHemicubes = 0;  ///< of them, vertices refinement added (beside another surface)
  int doubted = 0;       ///< of them, vertices the cache would interpolate from disagreeing ones
  /// Vertices of the mesh before refinement that take their light from the cache's gathering
  /// ones instead of gathering (GatherCache).
  int interpolated = 0;
  long factors = 0;      ///< non-zero form factors over all of them
  bool iterated = false; ///< the vertex system solved (false: gathered once, over memory)
  int iterations = 0;    ///< BiCGSTAB iterations
  double residual = 0;   ///< relative residual at the end (largest channel)
  /// The hemicubes' own time (rendered ahead: from the mesh on, beside the rays and the
  /// shots) and the iteration's.
  double hemicubeSeconds = 0, solveSeconds = 0;
  bool renderedAhead = false;  ///< the hemicubes rendered beside the rays and shots (GatherAhead)
  bool timedOut = false;  ///< the deadline came before every hemicube was rendered
};

/// One gathering vertex's form factors to the elements its hemicube sees.
struct GatherRow {
  std::vector<int> elements;
  std::vector<float> factors;
};

/// The hemicubes of the mesh the gather draws (the mesh as built before refinement): they
/// depend on that mesh alone, not on the light, so they can render while the rays are cast and
/// the start is shot (GatherAhead).
struct GatherRows {
  std::vector<GatherRow> rows;   ///< per vertex of the drawn mesh (empty: black, interpolated, or let go)
  std::vector<double> nearest;   ///< per vertex, Hemicube::nearest where rendered
  std::vector<char> rendered;    ///< per vertex, whether its hemicube was rendered
  GatherCache cache;             ///< which vertices of the drawn mesh gather, and how the others interpolate
  std::vector<glm::dvec3> once;  ///< per vertex, its row over `y` (renderGatherRows), if given
  long factors = 0;              ///< non-zero factors over all rows
  bool kept = true;              ///< false: the rows outgrew options.memoryBytes and were let go
  bool timedOut = false;         ///< options.deadline came first (or the rendering was cancelled)
  double seconds = 0;            ///< how long they took to render
};

/// Renders the hemicube of every vertex of `drawn` that is not black, from its probe on drawn
/// (off its surface and inwards, towards drawn's elements round it), over drawn's elements.
/// With `y` (per element of drawn), each row is also gathered over it at once
/// (GatherRows::once), so that rows over the memory budget can be let go as they come; without
/// it, rendering stops once they outgrow the budget (kept false: they serve nothing). Stops
/// early once `cancel` is set.
GatherRows renderGatherRows(const PatchMesh& drawn, double sceneSize, const GatherOptions& options,
                            const std::vector<glm::dvec3>* y = nullptr, const std::atomic<bool>* cancel = nullptr);

/// renderGatherRows on threads of its own, from construction on, while the caller goes on
/// (meshScene casts the rays and refines meanwhile, and the start is shot): the gather then
/// only iterates. The threads add to the caller's; the rows are what rendering them later
/// gives, bit for bit.
class GatherAhead {
 public:
  GatherAhead(std::shared_ptr<const PatchMesh> drawn, double sceneSize, const GatherOptions& options);
  /// Stops rendering (what is left is not needed) and waits for the threads.
  ~GatherAhead();
  GatherAhead(const GatherAhead&) = delete;
  GatherAhead& operator=(const GatherAhead&) = delete;

  /// The rows, once rendered (waits for them; rethrows what rendering threw). One caller at
  /// a time (the solve's thread).
  const GatherRows& rows();
  /// The mesh they draw.
  const PatchMesh& drawn() const { return *drawn_; }

 private:
  std::shared_ptr<const PatchMesh> drawn_;
  std::atomic<bool> cancel_{false};
  std::future<GatherRows> rendering_;
  std::optional<GatherRows> rows_;
  std::exception_ptr failed_;
};

/// The radiosity shown at each vertex of `mesh`: its surface's emission plus x (above).
/// `start`: the light each vertex reflects, as the progressive solution shows it (the
/// iteration's start and, over memory, what the single gather gathers). `direct`: per vertex,
/// the direct light by rays, or null.
/// `base`: the mesh as built before refinement (or null): its vertices gather, and the
/// hemicubes draw its elements, each valued as the area-weighted mean of its parts.
/// `rendered`: the drawn mesh's rows if rendered already (GatherAhead), else null.
/// `ownHemicube`: per vertex, whether (added by refinement) it gathers through its own hemicube
/// (nearSurfaces), or null: none does. Past the deadline with the drawn mesh's rows all there,
/// those interpolate their base corners instead.
/// Empty if options.deadline came before every hemicube was rendered (stats: timedOut).
std::vector<glm::dvec3> finalGather(const PatchMesh& mesh, const PatchMesh* base, double sceneSize,
                                    const std::vector<glm::dvec3>& start, const std::vector<glm::dvec3>* direct,
                                    const GatherOptions& options, GatherStats* stats = nullptr,
                                    const GatherRows* rendered = nullptr,
                                    const std::vector<char>* ownHemicube = nullptr);

/// What the gather would cost, from kGatherWorkProbes of its vertices spread over the mesh.
/// Deterministic: the same mesh gives the same figures on any machine.
struct GatherEstimate {
  /// The triangles its hemicubes would sort to their faces (regions' outlines and elements
  /// left as they are): a hemicube that culls hidden triangles (interiors) costs what it sees,
  /// one that does not every triangle.
  double drawn = 0;
  /// The pixels that would show a flat region, each resolved to its element.
  double located = 0;
  /// The non-zero factors of all its rows (GatherOptions::memoryBytes keeps them to iterate).
  double factors = 0;
  /// Whether its hemicubes cull hidden triangles (Hemicube::cullingPays).
  bool culled = false;
  /// The gathering vertices it is for.
  double vertices = 0;

  /// The same for `count` gathering vertices like these (vertices refinement added that
  /// gather through their own hemicubes).
  GatherEstimate forVertices(double count) const {
    GatherEstimate out = *this;
    const double scale = vertices > 0 ? count / vertices : 0;
    out.drawn *= scale;
    out.located *= scale;
    out.factors *= scale;
    out.vertices = count;
    return out;
  }

  /// The seconds it would take on `workers` cores of this machine class.
  double seconds(int workers) const {
    return (drawn * (culled ? kCulledGatherSecondsPerTriangle : kGatherSecondsPerTriangle) +
            located * kGatherSecondsPerLocatedPixel) /
           double(workers);
  }
  /// Whether the rows would fit the memory budget: the vertex system is iterated to its own
  /// solution, whatever the progressive start.
  bool iterates(const GatherOptions& options) const {
    return factors * double(sizeof(int) + sizeof(float)) <= double(options.memoryBytes);
  }
};
GatherEstimate estimateGather(const PatchMesh& mesh, double sceneSize, const GatherOptions& options);

/// The emission and reflectance of each vertex's surface (vertices belong to one side of one
/// surface); zero for an isolated vertex.
std::vector<glm::dvec3> vertexEmission(const PatchMesh& mesh);
std::vector<glm::dvec3> vertexReflectance(const PatchMesh& mesh);

/// Each element's value as the mean of its corners' values.
std::vector<glm::dvec3> elementMeans(const PatchMesh& mesh, const std::vector<glm::dvec3>& atVertices);

}  // namespace rad
