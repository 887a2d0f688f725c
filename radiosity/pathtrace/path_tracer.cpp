#include "radiosity/pathtrace/path_tracer.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/base/parallel.h"

namespace rad::pathtrace {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A cosine-weighted direction about unit n (Malley's method), in the orthonormal basis of
/// Duff et al. 2017.
glm::dvec3 cosineDirection(const glm::dvec3& n, double u0, double u1) {
  const double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), b = n.x * n.y * a;
  const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 s(b, sign + n.y * n.y * a, -n.y);
  const double r = std::sqrt(u0), phi = 2 * kPi * u1;
  return r * std::cos(phi) * t + r * std::sin(phi) * s + std::sqrt(std::max(0.0, 1 - u0)) * n;
}

/// Veach's power heuristic: the weight of a sample drawn with density a where b also could have.
double powerHeuristic(double a, double b) {
  if (!(a < HUGE_VAL)) return 1;
  return a * a / (a * a + b * b);
}

/// The largest channel of v.
double maxOf(const glm::dvec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

/// The standard error of the mean of n samples with this sum and sum of squares.
double standardError(double sum, double sumSq, long n) {
  const double mean = sum / double(n);
  return std::sqrt(std::max(0.0, sumSq / double(n) - mean * mean) / double(n - 1));
}

/// The running sums of one point's path estimates.
struct PathSums {
  glm::dvec3 sum{0.0}, sumSq{0.0};
  long count = 0;

  /// Adds one path's estimate b.
  void add(const glm::dvec3& b) {
    sum += b;
    sumSq += b * b;
  }

  /// The largest relative standard error over the channels whose mean is not zero.
  double relativeError() const {
    double worst = 0;
    for (int c = 0; c < 3; ++c)
      if (const double mean = sum[c] / double(count); mean > 0)
        worst = std::max(worst, standardError(sum[c], sumSq[c], count) / mean);
    return worst;
  }

  /// The mean and its standard error per channel.
  PointEstimate estimate() const {
    PointEstimate e;
    e.paths = count;
    e.B = sum / double(count);
    for (int c = 0; c < 3; ++c) e.standardError[c] = count > 1 ? standardError(sum[c], sumSq[c], count) : 0.0;
    return e;
  }
};

/// Russian roulette keeps the throughput T near where it started (tStart): false ends the
/// path; a surviving path's T is raised by the odds it survived.
bool survives(glm::dvec3& T, double tStart, Random& rng) {
  const double survive = std::min(1.0, maxOf(T) / tStart);
  if (rng.next() >= survive) return false;
  T /= survive;
  return true;
}

/// Whether the path goes on after bounce `depth`: Russian roulette from kRouletteDepth on,
/// and never with no throughput left.
bool goesOn(glm::dvec3& T, double tStart, int depth, Random& rng) {
  if (depth >= kRouletteDepth && !survives(T, tStart, rng)) return false;
  return maxOf(T) > 0;
}

/// The side of light sample s that faces d (from the lit point to s.point) and the cosine
/// there, positive when s emits towards the lit point.
std::pair<glm::dvec3, double> facingSide(const LightSample& s, const glm::dvec3& d) {
  double cy = -glm::dot(s.normal, d);
  const glm::dvec3 lightSide = cy < 0 ? -s.normal : s.normal;
  if (s.twoSided) cy = std::abs(cy);
  return {lightSide, cy};
}

}  // namespace

void PathTracer::addLightSample(const glm::dvec3& x, const glm::dvec3& nx, const glm::dvec3& T,
                                Random& rng, glm::dvec3& B) const {
  const double u0 = rng.next(), u1 = rng.next(), u2 = rng.next();
  const LightSample s = scene_.sampleLight(u0, u1, u2);
  const glm::dvec3 d = s.point - x;
  const double r2 = glm::dot(d, d), cx = glm::dot(nx, d);
  const auto [lightSide, cy] = facingSide(s, d);
  if (!(cx > 0 && cy > 0 && s.emission != glm::dvec3(0.0)) ||
      scene_.occluded(x + kRayOffset * nx, s.point + kRayOffset * lightSide))
    return;
  const double r = std::sqrt(r2);
  const double pLight = s.pdf * r2 * r / cy, pBounce = cx / (r * kPi);  // per solid angle
  // E/π · cosθ cosθ' / r² / pdf, cosθ = cx/r, cosθ' = cy/r.
  B += T * s.emission * (cx * cy / (kPi * r2 * r2 * s.pdf)) * powerHeuristic(pLight, pBounce);
}

void PathTracer::addBounceEmission(const glm::dvec3& x, const glm::dvec3& nx, const glm::dvec3& w,
                                   const TraceHit& hit, const glm::dvec3& T, glm::dvec3& B) const {
  const double lightPdf = scene_.lightPdf(hit.triangle);
  if (!(lightPdf > 0)) return;
  const TraceTriangle& t = scene_.triangle(hit.triangle);
  // The bounce's estimate of π·L is the exitance E where it lands.
  const glm::dvec3 d = hit.point - x;
  const double r2 = glm::dot(d, d), cy = std::abs(glm::dot(t.normal, d)), r = std::sqrt(r2);
  const double pLight = lightPdf * r2 * r / cy, pBounce = glm::dot(nx, w) / kPi;
  B += T * scene_.material(t.surface).emission * powerHeuristic(pBounce, pLight);
}

bool PathTracer::bounce(glm::dvec3& x, glm::dvec3& nx, glm::dvec3& T, Random& rng, glm::dvec3& B) const {
  // Light reaches x two ways, each weighted by the power heuristic (Veach 1997): from a
  // point on the emitters chosen by power (next-event estimation), and where the cosine-
  // weighted bounce lands on an emitter. Either alone has unbounded variance somewhere: the
  // first beside an emitter's edge (1/r²), the second for small bright emitters.
  if (scene_.emits()) addLightSample(x, nx, T, rng, B);
  // One draw per statement: a call's arguments are evaluated in an unspecified order, and the
  // stream must give the same paths whatever the compiler (this is the order GCC took).
  const double v = rng.next(), u = rng.next();
  const glm::dvec3 w = cosineDirection(nx, u, v);
  const TraceHit hit = scene_.intersect(x + kRayOffset * nx, w, HUGE_VAL);
  if (hit.triangle < 0) return false;  // escaped
  if (!scene_.reflects(hit)) return false;  // the back of a one-sided surface absorbs
  addBounceEmission(x, nx, w, hit, T, B);
  T *= scene_.material(scene_.triangle(hit.triangle).surface).reflectance;
  x = hit.point;
  nx = scene_.sideNormal(hit);
  return true;
}

glm::dvec3 PathTracer::tracePath(const glm::dvec3& p, const glm::dvec3& n, int surface,
                                 Random& rng) const {
  const Material& start = scene_.material(surface);
  glm::dvec3 B = start.emission, T = start.reflectance;  // B = E + ρ·H, H estimated below
  const double tStart = maxOf(T);
  if (!(tStart > 0)) return B;
  glm::dvec3 x = p, nx = n;
  for (int depth = 1;; ++depth)
    if (!bounce(x, nx, T, rng, B) || !goesOn(T, tStart, depth, rng)) break;
  return B;
}

PointEstimate PathTracer::estimate(const SurfacePoint& point, uint64_t stream,
                                   const TraceOptions& options) const {
  Random rng = Random::stream(options.seed, stream);
  const glm::dvec3 p = scene_.toLocal(point.position), n = glm::normalize(point.normal);
  const long target = options.paths > 0 ? options.paths : std::max(options.maxPaths, 2L);
  PathSums sums;
  while (sums.count < target) {
    const long batch = std::min(kPathBatch, target - sums.count);
    for (long i = 0; i < batch; ++i) sums.add(tracePath(p, n, point.surface, rng));
    sums.count += batch;
    if (options.paths <= 0 && sums.count >= options.minPaths && sums.relativeError() <= options.relativeError)
      break;
  }
  traced_ += sums.count;
  return sums.estimate();
}

std::vector<PointEstimate> PathTracer::estimate(const std::vector<SurfacePoint>& points,
                                                const TraceOptions& options) const {
  std::vector<PointEstimate> out(points.size());
  std::atomic<size_t> done{0};
  const double total = double(std::max<size_t>(1, points.size()));
  if (options.progress) options.progress(0.0);
  // Worker 0 is the calling thread: it reports the share done after each of its points.
  parallelFor(points.size(), workerCount(options.workers), [&](size_t i, int worker) {
    out[i] = estimate(points[i], i, options);
    const size_t finished = ++done;
    if (worker == 0 && options.progress) options.progress(double(finished) / total);
  });
  if (options.progress) options.progress(1.0);
  return out;
}

}  // namespace rad::pathtrace
