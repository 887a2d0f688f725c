#include "radiosity/gather/final_gather.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include <glm/common.hpp>

#include "mesh/base/parallel.h"
#include "mesh/base/progress.h"
#include "mesh/mesh_settings.h"
#include "radiosity/formfactors/flat_regions.h"
#include "radiosity/formfactors/hemicube.h"
#include "radiosity/gather/gather_points.h"
#include "radiosity/light/direct_light.h"

namespace rad {

namespace {

using Field = std::vector<glm::dvec3>;
using Clock = std::chrono::steady_clock;

/// The gather's hemicubes turn by their own stream of rotations, apart from the shooters'.
constexpr uint64_t kGatherStream = 0x6761746865720000ull;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The rows the vertex system takes: per vertex of the refined mesh, the row it gathers
/// through (null: it does not gather), or none once they outgrew the memory budget.
struct Rows {
  std::vector<const GatherRow*> of;
  bool kept = true;
};

/// Σⱼ F_vj·y_j over one row.
glm::dvec3 gatherRow(const GatherRow& row, const Field& y) {
  glm::dvec3 sum(0.0);
  for (size_t k = 0; k < row.elements.size(); ++k) sum += double(row.factors[k]) * y[size_t(row.elements[k])];
  return sum;
}

/// The hemicube's factors from vertex v of `mesh` (off its surface and inwards, as the rays
/// start).
void factorsAt(const PatchMesh& mesh, double sceneSize, unsigned seed, int v, Hemicube& cube, FormFactors& out) {
  const DirectLight::Probe probe = vertexProbe(mesh, TriMesh::VertexHandle(v));
  cube.compute(offSurface(probe, sceneSize), probe.normal, hemicubeRotation(seed, kGatherStream + uint64_t(v), 0), out);
}

/// The farthest a vertex takes gathering vertices' light from: kGatherFarthestShare of the
/// element edge, the default one's if the options do not say.
double farthestInterpolated(const GatherOptions& options, double sceneSize) {
  return kGatherFarthestShare * (options.elementEdge > 0 ? options.elementEdge : sceneSize / kDefaultElementsPerDiagonal);
}

/// The chance that vertex v of `mesh`, whose hemicube showed its nearest surface `nearest` away, gathers
/// (GatherCache): its share of the area over the area a gathering vertex there covers, about
/// kGatherCoverShare of π·(accuracy·R)².
double gatherShare(const PatchMesh& mesh, int v, double nearest, double sceneSize, const GatherOptions& options) {
  const double accuracy = options.accuracy;
  if (accuracy <= 0) return 1;
  double area = 0;
  for (auto f : mesh.mesh.vf_range(TriMesh::VertexHandle(v))) area += mesh.area(f.idx()) / 3;
  const double R = std::min(nearest, maxGatherReach(sceneSize, accuracy, farthestInterpolated(options, sceneSize)));
  const double covers = kGatherCoverShare * M_PI * (accuracy * R) * (accuracy * R);
  return std::min(1.0, area / covers);
}

/// The vertices of `mesh` that gather, as the mesh the hemicubes draw: every one not black.
std::vector<int> gatheringVertices(const PatchMesh& mesh) {
  const Field rho = vertexReflectance(mesh);
  std::vector<int> out;
  for (size_t v = 0; v < rho.size(); ++v)
    if (rho[v] != glm::dvec3(0.0)) out.push_back(int(v));
  return out;
}

/// Renders the hemicubes of `mesh`'s vertices `which` over `drawn`'s elements into `out`
/// (rows per vertex of mesh), each gathered over y at once if given, and let go once the
/// rows outgrow the budget. `what`: the vertices, as the progress line names them.
void renderRows(const std::string& what, const PatchMesh& mesh, const PatchMesh& drawn, double sceneSize,
                const std::vector<int>& which, const GatherOptions& options, const Field* y,
                const std::atomic<bool>* cancel, GatherRows& out) {
  const auto clock = Clock::now();
  const FlatRegions regions(drawn, sceneSize);
  const int workers = workerCount(options.workers);
  std::vector<std::unique_ptr<Hemicube>> cubes;
  std::vector<FormFactors> scratch(static_cast<size_t>(workers));
  for (int w = 0; w < workers; ++w) cubes.push_back(std::make_unique<Hemicube>(regions, options.resolution, sceneSize));
  out.rows.resize(mesh.mesh.n_vertices());
  out.nearest.resize(mesh.mesh.n_vertices(), 0.0);
  out.rendered.resize(mesh.mesh.n_vertices(), 0);
  if (y && out.once.empty()) out.once.assign(mesh.mesh.n_vertices(), glm::dvec3(0.0));
  std::atomic<long> factors{out.factors};
  std::atomic<bool> late{false}, over{false};
  const long budget = long(options.memoryBytes / (sizeof(int) + sizeof(float)));
  StageProgress progress("final gather: hemicubes at " + what, which.size());  // said by the caller's worker
  parallelFor(which.size(), workers, [&](size_t k, int worker) {
    if (late || over) return;
    if (worker == 0) progress.update(k);
    if ((options.deadline && Clock::now() > *options.deadline) || (cancel && *cancel)) {
      late = true;
      return;
    }
    const int v = which[k];
    FormFactors& f = scratch[size_t(worker)];
    factorsAt(mesh, sceneSize, options.seed, v, *cubes[size_t(worker)], f);
    out.nearest[size_t(v)] = cubes[size_t(worker)]->nearest();
    out.rendered[size_t(v)] = 1;
    GatherRow& row = out.rows[size_t(v)];
    row.elements = f.elements;
    row.factors.assign(f.factors.begin(), f.factors.end());
    if (y) out.once[size_t(v)] = gatherRow(row, *y);
    if ((factors += long(f.elements.size())) <= budget) return;
    row = GatherRow();
    if (!y) over = true;  // without y, rows let go serve nothing: the gather renders them again
  }, 16);
  out.factors = factors;
  out.timedOut = out.timedOut || late;
  out.kept = out.kept && factors <= budget && !over;
  if (!out.kept) out.rows.clear();
  out.seconds += secondsSince(clock);
}

}  // namespace

GatherRows renderGatherRows(const PatchMesh& drawn, double sceneSize, const GatherOptions& options, const Field* y,
                            const std::atomic<bool>* cancel) {
  GatherRows out;
  out.cache = chooseGathering(drawn, gatheringVertices(drawn), options.accuracy, sceneSize,
                              farthestInterpolated(options, sceneSize),
                              [&](const std::vector<int>& which, std::vector<double>& nearest) {
                                renderRows("gathering vertices", drawn, drawn, sceneSize, which, options, y, cancel, out);
                                for (int v : which) nearest[size_t(v)] = out.nearest[size_t(v)];
                                return !out.timedOut && (out.kept || y);
                              });
  return out;
}

GatherAhead::GatherAhead(std::shared_ptr<const PatchMesh> drawn, double sceneSize, const GatherOptions& options)
    : drawn_(std::move(drawn)) {
  rendering_ = std::async(std::launch::async, [this, sceneSize, options, sink = currentProgressSink()] {
    const ProgressScope progress(sink);  // the hemicubes' progress said as the caller's stages are
    return renderGatherRows(*drawn_, sceneSize, options, nullptr, &cancel_);
  });
}

GatherAhead::~GatherAhead() {
  cancel_ = true;
  if (rendering_.valid()) rendering_.wait();
}

const GatherRows& GatherAhead::rows() {
  if (!rows_ && !failed_) {
    try {
      rows_ = rendering_.get();
    } catch (...) {
      failed_ = std::current_exception();
    }
  }
  if (failed_) std::rethrow_exception(failed_);
  return *rows_;
}

namespace {

/// The value of each element the hemicubes draw as a weighted sum of vertex values: the
/// mean of its corners, or, drawing the mesh as built before refinement, the area-weighted
/// mean of its parts' corner means.
struct Interpolation {
  std::vector<std::vector<std::pair<int, double>>> terms;  // per drawn element

  Field apply(const Field& x) const {
    Field y(terms.size(), glm::dvec3(0.0));
    for (size_t j = 0; j < terms.size(); ++j)
      for (const auto& [v, w] : terms[j]) y[j] += w * x[size_t(v)];
    return y;
  }
};

Interpolation interpolation(const PatchMesh& mesh, const PatchMesh* base) {
  Interpolation out;
  out.terms.resize(size_t(base ? base->elementCount() : mesh.elementCount()));
  for (auto f : mesh.mesh.faces()) {
    const int e = f.idx(), j = base ? mesh.base(e) : e;
    const double w = base ? mesh.area(e) / (3 * base->area(j)) : 1.0 / 3;
    for (auto v : mesh.mesh.fv_range(f)) out.terms[size_t(j)].emplace_back(v.idx(), w);
  }
  return out;
}

/// F·y at every vertex: gathered over y at the gathering vertices, interpolated at the others.
Field gathered(const Rows& rows, const GatherPoints& points, const Field& y, int workers) {
  Field atPoints(points.at.size(), glm::dvec3(0.0));
  parallelFor(atPoints.size(), workers, [&](size_t v, int) {
    if (rows.of[v]) atPoints[v] = gatherRow(*rows.of[v], y);
  }, 256);
  return points.spread(atPoints);
}

/// The vertex system x = d + ρ·F·W·x as an operator: A·x = x − ρ·F·W·x.
struct VertexSystem {
  const Rows& rows;
  const GatherPoints& points;
  const Interpolation& W;
  const Field& rho;
  int workers;

  Field apply(const Field& x) const {
    const Field g = gathered(rows, points, W.apply(x), workers);
    Field out(x.size());
    for (size_t v = 0; v < x.size(); ++v) out[v] = x[v] - rho[v] * g[v];
    return out;
  }
};

glm::dvec3 dot(const Field& a, const Field& b) {
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i];
  return sum;
}

/// a / b per channel, 0 where b is 0 (a channel that has converged or carries nothing).
glm::dvec3 safeDivide(const glm::dvec3& a, const glm::dvec3& b) {
  glm::dvec3 out(0.0);
  for (int c = 0; c < 3; ++c) out[c] = b[c] != 0 ? a[c] / b[c] : 0.0;
  return out;
}

/// a + s·b, per channel.
Field axpy(const Field& a, const glm::dvec3& s, const Field& b) {
  Field out(a.size());
  for (size_t i = 0; i < a.size(); ++i) out[i] = a[i] + s * b[i];
  return out;
}

/// The largest channel's |r| / |b|.
double relativeResidual(const Field& r, const glm::dvec3& bNorm2) {
  const glm::dvec3 ratio = safeDivide(dot(r, r), bNorm2);
  return std::sqrt(std::max({ratio.x, ratio.y, ratio.z}));
}

/// BiCGSTAB (van der Vorst 1992) on the three channels at once, each with its own scalars;
/// x holds the start and gets the solution.
void solveSystem(const VertexSystem& A, const Field& b, Field& x, const GatherOptions& options, GatherStats& stats) {
  const glm::dvec3 bNorm2 = dot(b, b);
  Field r = axpy(b, glm::dvec3(-1.0), A.apply(x));
  const Field rHat = r;
  Field p(x.size(), glm::dvec3(0.0)), v(x.size(), glm::dvec3(0.0));
  glm::dvec3 rhoOld(1.0), alpha(1.0), omega(1.0);
  stats.residual = relativeResidual(r, bNorm2);
  auto inTime = [&] { return !options.deadline || Clock::now() <= *options.deadline; };
  for (stats.iterations = 0; stats.iterations < options.maxIterations && stats.residual > options.tolerance && inTime();
       ++stats.iterations) {
    const glm::dvec3 rho = dot(rHat, r);
    const glm::dvec3 beta = safeDivide(rho, rhoOld) * safeDivide(alpha, omega);
    for (size_t i = 0; i < p.size(); ++i) p[i] = r[i] + beta * (p[i] - omega * v[i]);
    v = A.apply(p);
    alpha = safeDivide(rho, dot(rHat, v));
    const Field s = axpy(r, -alpha, v);
    // Half a step may be enough: s is the residual of x + α·p.
    if (const double half = relativeResidual(s, bNorm2); half <= options.tolerance) {
      for (size_t i = 0; i < x.size(); ++i) x[i] += alpha * p[i];
      stats.residual = half;
      ++stats.iterations;
      break;
    }
    const Field t = A.apply(s);
    omega = safeDivide(dot(t, s), dot(t, t));
    for (size_t i = 0; i < x.size(); ++i) x[i] += alpha * p[i] + omega * s[i];
    r = axpy(s, -omega, t);
    rhoOld = rho;
    stats.residual = relativeResidual(r, bNorm2);
  }
}

/// What each drawn element sends that the gather takes: its reflected light `reflected`, and
/// its emission too when no rays count it (`withEmission`).
Field sent(const PatchMesh& drawn, Field reflected, bool withEmission) {
  if (withEmission)
    for (int e = 0; e < drawn.elementCount(); ++e) reflected[size_t(e)] += drawn.emission(e);
  return reflected;
}

/// The rays' direct light per vertex, or zeros without rays.
Field directOrZero(const Field* direct, size_t vertices) {
  return direct ? *direct : Field(vertices, glm::dvec3(0.0));
}

/// a + ρ·b per vertex.
Field plus(Field a, const Field& rho, const Field& b) {
  for (size_t v = 0; v < a.size(); ++v) a[v] += rho[v] * b[v];
  return a;
}

/// Without rays, the vertex system's d: what each vertex reflects of the emitters' emission
/// (ρ·F·E), from the kept rows.
Field emittersGathered(const PatchMesh& drawn, const Rows& rows, const GatherPoints& points, const Field& rho, int workers) {
  Field emitted(size_t(drawn.elementCount()));
  for (int e = 0; e < drawn.elementCount(); ++e) emitted[size_t(e)] = drawn.emission(e);
  return plus(Field(rho.size(), glm::dvec3(0.0)), rho, gathered(rows, points, emitted, workers));
}

/// A property of each vertex's surface, from its first element (vertices belong to one side of
/// one surface); zero for an isolated vertex.
template <class Property>
Field ofVertexSurface(const PatchMesh& mesh, Property property) {
  Field out(mesh.mesh.n_vertices(), glm::dvec3(0.0));
  for (auto v : mesh.mesh.vertices())
    for (auto f : mesh.mesh.vf_range(v)) {
      out[size_t(v.idx())] = property(f.idx());
      break;
    }
  return out;
}

}  // namespace

std::vector<glm::dvec3> vertexEmission(const PatchMesh& mesh) {
  return ofVertexSurface(mesh, [&](int e) { return mesh.emission(e); });
}

std::vector<glm::dvec3> vertexReflectance(const PatchMesh& mesh) {
  return ofVertexSurface(mesh, [&](int e) { return mesh.reflectance(e); });
}

std::vector<glm::dvec3> elementMeans(const PatchMesh& mesh, const std::vector<glm::dvec3>& atVertices) {
  Field out;
  out.reserve(size_t(mesh.elementCount()));
  for (auto f : mesh.mesh.faces()) {
    glm::dvec3 sum(0.0);
    for (auto v : mesh.mesh.fv_range(f)) sum += atVertices[size_t(v.idx())];
    out.push_back(sum / 3.0);
  }
  return out;
}

namespace {

/// The drawn mesh's rows: those the cache chose, and those rendered where its gathering
/// vertices disagreed.
struct DrawnRows {
  const GatherRows& chosen;
  const GatherRows& doubted;
  const Field& y;

  bool isDoubted(int d) const { return size_t(d) < doubted.rendered.size() && doubted.rendered[size_t(d)]; }
  const GatherRow& row(int d) const { return isDoubted(d) ? doubted.rows[size_t(d)] : chosen.rows[size_t(d)]; }
  /// Its row over y.
  glm::dvec3 once(int d) const {
    if (isDoubted(d)) return doubted.once[size_t(d)];
    return chosen.once.empty() ? gatherRow(chosen.rows[size_t(d)], y) : chosen.once[size_t(d)];
  }
};

/// The gathering vertices that are not the drawn mesh's: they render hemicubes of their own.
std::vector<int> lonersOf(const GatherPoints& points) {
  std::vector<int> out;
  for (size_t v = 0; v < points.at.size(); ++v)
    if (points.at[v] && points.drawn[v] < 0) out.push_back(int(v));
  return out;
}

}  // namespace

GatherEstimate estimateGather(const PatchMesh& mesh, double sceneSize, const GatherOptions& options) {
  const std::vector<int> gathering = gatheringVertices(mesh);
  GatherEstimate out;
  if (gathering.empty()) return out;
  const FlatRegions regions(mesh, sceneSize);
  Hemicube cube(regions, options.resolution, sceneSize);
  FormFactors f;
  const size_t probes = std::min(gathering.size(), size_t(kGatherWorkProbes));
  double share = 0;  // of the probes, the share that would gather (GatherCache)
  for (size_t k = 0; k < probes; ++k) {
    const int v = gathering[(2 * k + 1) * gathering.size() / (2 * probes)];
    factorsAt(mesh, sceneSize, options.seed, v, cube, f);
    share += gatherShare(mesh, v, cube.nearest(), sceneSize, options);
    out.drawn += double(cube.sorted());
    out.located += double(cube.counts().located);
    out.factors += double(f.elements.size());
  }
  out.culled = cube.culling() == HemicubeCulling::Hidden;
  out.vertices = double(gathering.size()) * share / double(probes);
  const double perProbe = out.vertices / double(probes);
  out.drawn *= perProbe;
  out.located *= perProbe;
  out.factors *= perProbe;
  return out;
}

std::vector<glm::dvec3> finalGather(const PatchMesh& mesh, const PatchMesh* base, double sceneSize,
                                    const std::vector<glm::dvec3>& start, const std::vector<glm::dvec3>* direct,
                                    const GatherOptions& options, GatherStats* statsOut, const GatherRows* rendered,
                                    const std::vector<char>* ownHemicube) {
  GatherStats stats;
  const Field rho = vertexReflectance(mesh), emission = vertexEmission(mesh);
  const PatchMesh& drawn = base ? *base : mesh;
  const int workers = workerCount(options.workers);
  const Interpolation W = interpolation(mesh, base);
  const Field y = sent(drawn, W.apply(start), !direct);
  // The drawn mesh's rows: rendered already, or now (gathered over y as they come, in case
  // they outgrow the memory budget); and the rows of gathering vertices that are not the
  // drawn mesh's (a base corner refinement lost), rendered from their own probes.
  GatherRows now;
  if (!rendered || !rendered->kept) now = renderGatherRows(drawn, sceneSize, options, &y);
  const GatherRows& ofDrawn = rendered && rendered->kept ? *rendered : now;
  // The drawn mesh's vertices whose light the cache would interpolate from gathering vertices
  // that disagree over y gather too (rows of their own, `doubted`).
  GatherRows doubted;
  doubted.factors = ofDrawn.factors;  // counted against the same budget
  DrawnInterpolation interpolated;
  if (ofDrawn.cache.complete) {
    interpolated = ofDrawn.cache.from;
    const std::vector<int> doubtful = disagreeing(ofDrawn.cache, [&](int d) {
      const glm::dvec3 h = ofDrawn.once.empty() ? gatherRow(ofDrawn.rows[size_t(d)], y) : ofDrawn.once[size_t(d)];
      return h.x + h.y + h.z;
    }, options.agreement);
    if (!doubtful.empty()) renderRows("doubted vertices", drawn, drawn, sceneSize, doubtful, options, &y, nullptr, doubted);
    if (doubted.timedOut) {  // past the deadline: they interpolate, as they would without the doubt
      doubted = GatherRows{};
      doubted.factors = ofDrawn.factors;
    } else {
      for (int v : doubtful) interpolated[size_t(v)] = {{v, 1.0}};
    }
    for (size_t v = 0; v < interpolated.size(); ++v)
      if (!interpolated[v].empty() && !(interpolated[v].size() == 1 && interpolated[v][0].first == int(v)))
        ++stats.interpolated;
  }
  const DrawnRows drawnRows{ofDrawn, doubted, y};
  const DrawnInterpolation* drawnFrom = ofDrawn.cache.complete ? &interpolated : nullptr;
  GatherPoints points = gatherPoints(mesh, base, rho, ownHemicube, drawnFrom);
  GatherRows own;
  own.factors = doubted.factors;  // counted against the same budget
  std::vector<int> loners = lonersOf(points);
  if (!loners.empty()) renderRows("refined vertices", mesh, drawn, sceneSize, loners, options, &y, nullptr, own);
  // Past the deadline with the drawn mesh's rows all there, the vertices refinement added
  // interpolate their base corners, as they would without hemicubes of their own.
  if (own.timedOut && !ofDrawn.timedOut && ownHemicube) {
    GatherPoints interpolating = gatherPoints(mesh, base, rho, nullptr, drawnFrom);
    if (lonersOf(interpolating).empty()) {
      points = std::move(interpolating);
      loners.clear();
      own = GatherRows{};
      own.factors = doubted.factors;
    }
  }
  stats.points = points.count();
  stats.ownHemicubes = int(loners.size());
  stats.factors = own.factors;
  stats.doubted = int(std::count(doubted.rendered.begin(), doubted.rendered.end(), 1));
  stats.timedOut = ofDrawn.timedOut || doubted.timedOut || own.timedOut;
  stats.hemicubeSeconds = ofDrawn.seconds + doubted.seconds + own.seconds;
  stats.renderedAhead = rendered && rendered->kept;
  if (stats.timedOut) {
    if (statsOut) *statsOut = stats;
    return {};
  }
  const auto clock = Clock::now();
  Rows rows;
  rows.kept = ofDrawn.kept && doubted.kept && own.kept;
  if (rows.kept) {
    rows.of.assign(points.at.size(), nullptr);
    for (size_t v = 0; v < points.at.size(); ++v)
      if (points.at[v]) rows.of[v] = points.drawn[v] >= 0 ? &drawnRows.row(points.drawn[v]) : &own.rows[v];
  }
  // The single gather over y at each gathering vertex: rows rendered ahead (kept, or they
  // would have been rendered now) have not met y yet, even if the loners' went over the budget.
  Field once(points.at.size(), glm::dvec3(0.0));
  parallelFor(once.size(), workers, [&](size_t v, int) {
    if (!points.at[v]) return;
    const int d = points.drawn[v];
    once[v] = d < 0 ? own.once[v] : drawnRows.once(d);
  }, 256);
  Field x = plus(directOrZero(direct, rho.size()), rho, points.spread(once));
  if (rows.kept) {
    const Field d = direct ? *direct : emittersGathered(drawn, rows, points, rho, workers);
    solveSystem(VertexSystem{rows, points, W, rho, workers}, d, x, options, stats);
    stats.iterated = true;
  }
  stats.solveSeconds = secondsSince(clock);
  for (size_t v = 0; v < x.size(); ++v) x[v] = glm::max(x[v], glm::dvec3(0.0)) + emission[v];
  if (statsOut) *statsOut = stats;
  return x;
}

}  // namespace rad
