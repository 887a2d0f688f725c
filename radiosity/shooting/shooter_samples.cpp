#include "radiosity/shooting/shooter_samples.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "mesh/patch_mesh.h"
#include "mesh/scene/geometry.h"

namespace rad {
namespace {

/// A part of an element a shooter sample may take: `share` of the element's power.
struct Part {
  int element;
  double share, area;
  glm::dvec3 centroid;
  std::array<glm::dvec3, 3> corners;
};

/// Cuts triangle t into m² congruent triangles (each edge into m equal pieces).
void subdivide(int element, const std::array<glm::dvec3, 3>& t, int m, std::vector<Part>& out) {
  const double area = triangleArea(t[0], t[1], t[2]) / double(m * m), share = 1.0 / double(m * m);
  for (const auto& c : congruentSplit(t, m))
    out.push_back({element, share, area, (c[0] + c[1] + c[2]) / 3.0, c});
}

/// The longest axis (0, 1, 2) of the bounding box of the parts' centroids.
int longestAxis(const std::vector<Part>& parts) {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const Part& p : parts) {
    lo = glm::min(lo, p.centroid);
    hi = glm::max(hi, p.centroid);
  }
  glm::dvec3 extent = hi - lo;
  return extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
}

/// Where to cut the ordered parts so that the first `first` of `strata` strata get their
/// share of the area: the running area nearest that share.
size_t areaCut(const std::vector<Part>& parts, int strata, int first) {
  double total = 0;
  for (const Part& p : parts) total += p.area;
  const double target = total * first / strata;
  // Each side keeps at least as many parts as strata it must make, where it can.
  const size_t lowest = std::min<size_t>(first, parts.size() - 1);
  const size_t highest = std::max<size_t>(lowest, parts.size() - std::min<size_t>(strata - first, parts.size() - 1));
  size_t cut = lowest;
  double running = 0, best = HUGE_VAL;
  for (size_t i = 0; i < parts.size(); ++i) {
    running += parts[i].area;
    if (i + 1 >= lowest && i + 1 <= highest && std::abs(running - target) < best)
      best = std::abs(running - target), cut = i + 1;
  }
  return cut;
}

/// Splits `parts` into `strata` groups of about equal area: ordered along the longest axis of
/// their centroids' bounding box and cut where the running area best matches the share of the
/// first half of the strata; each half is split in turn.
void bisectByArea(std::vector<Part> parts, int strata, std::vector<std::vector<Part>>& out) {
  if (strata <= 1 || parts.size() <= 1) {
    out.push_back(std::move(parts));
    return;
  }
  const int axis = longestAxis(parts);
  std::stable_sort(parts.begin(), parts.end(), [&](const Part& a, const Part& b) {
    return a.centroid[axis] < b.centroid[axis];
  });
  const int first = strata / 2;
  const size_t cut = areaCut(parts, strata, first);
  std::vector<Part> tail(parts.begin() + long(cut), parts.end());
  parts.resize(cut);
  bisectByArea(std::move(parts), first, out);
  bisectByArea(std::move(tail), strata - first, out);
}

/// Whether point x lies in triangle c (counter-clockwise about `normal`), edges included.
bool insideTriangle(const std::array<glm::dvec3, 3>& c, const glm::dvec3& x, const glm::dvec3& normal) {
  bool inside = true;
  for (int k = 0; k < 3; ++k)
    inside = inside && glm::dot(glm::cross(c[(k + 1) % 3] - c[k], x - c[k]), normal) >= 0;
  return inside;
}

/// Where a stratum shoots from: its area-weighted centroid, or, should that fall outside its
/// parts (a stratum bent round a corner of the patch), the nearest part centroid.
glm::dvec3 stratumPoint(const std::vector<Part>& stratum, const glm::dvec3& normal) {
  glm::dvec3 centre(0.0);
  double area = 0;
  for (const Part& p : stratum) {
    centre += p.area * p.centroid;
    area += p.area;
  }
  centre /= area;
  glm::dvec3 nearest = stratum[0].centroid;
  for (const Part& p : stratum) {
    if (insideTriangle(p.corners, centre, normal)) return centre;
    if (glm::length(p.centroid - centre) < glm::length(nearest - centre)) nearest = p.centroid;
  }
  return nearest;
}

/// The elements (of total `area`) cut into enough m×m parts that they have at least `count`
/// of them, spread by area.
std::vector<Part> elementParts(const PatchMesh& mesh, const std::vector<int>& elements, double area, int count) {
  std::vector<Part> parts;
  for (int e : elements) {
    double quota = double(count) * mesh.area(e) / area;
    int m = std::max(1, int(std::ceil(std::sqrt(quota) - 1e-9)));
    subdivide(e, mesh.corners(e), m, parts);
  }
  return parts;
}

/// Adds a part's share of its element's power to the sample.
void addShare(ShooterSample& s, const Part& part) {
  if (!s.elements.empty() && s.elements.back() == part.element) {
    s.weights.back() += part.share;
    return;
  }
  auto at = std::find(s.elements.begin(), s.elements.end(), part.element);
  if (at != s.elements.end()) {
    s.weights[size_t(at - s.elements.begin())] += part.share;
  } else {
    s.elements.push_back(part.element);
    s.weights.push_back(part.share);
  }
}

/// Per element: its centroid, or none when the counts need no distances (neither patches by
/// proximity nor clusters).
std::vector<glm::dvec3> elementCentroids(const PatchMesh& mesh, const SolverOptions& options) {
  std::vector<glm::dvec3> out;
  if ((options.proximitySamples <= 0 && !options.clusters) || mesh.patches.empty()) return out;
  out.resize(size_t(mesh.elementCount()));
  for (int e = 0; e < mesh.elementCount(); ++e) out[size_t(e)] = mesh.centroid(e);
  return out;
}

}  // namespace

SampleCounter::SampleCounter(const PatchMesh& mesh, const SolverOptions& options) : mesh_(mesh), options_(options) {}

const PointTree& SampleCounter::centroids() const {
  std::call_once(built_, [this] {
    centroids_.emplace(elementCentroids(mesh_, options_));
    normal_.resize(centroids_->points().size());
    for (size_t e = 0; e < normal_.size(); ++e) normal_[e] = mesh_.normal(int(e));
  });
  return *centroids_;
}

const std::vector<glm::dvec3>& SampleCounter::normals() const {
  centroids();
  return normal_;
}

double SampleCounter::nearestFacing(int patch, double reach) const {
  const Patch& p = mesh_.patches[patch];
  const PointTree& tree = centroids();
  const std::vector<glm::dvec3>& normal = normals();
  return tree.nearest(p.centroid, p.centroid, reach, [&](int e) {
    // An element of another plane facing the patch (occlusion ignored).
    const glm::dvec3 d = tree.points()[size_t(e)] - p.centroid;
    if (glm::dot(d, p.normal) <= 1e-9 * p.diameter || glm::dot(d, normal[size_t(e)]) >= 0) return HUGE_VAL;
    return glm::length(d);
  });
}

int SampleCounter::proximityCount(double diameter, double nearest) const {
  const int fewest = options_.shooterSamples;
  const int most = std::max(fewest, options_.emitterSamples);
  if (!(nearest < HUGE_VAL)) return fewest;
  const double ratio = diameter / nearest;
  const double wanted = std::ceil(options_.proximitySamples * ratio * ratio - 1e-9);
  return int(std::min<double>(std::max<double>(wanted, fewest), most));
}

/// Only elements nearer than D·√(k / fewest) ask for more than the fewest points.
int SampleCounter::operator()(int patch) const {
  const Patch& p = mesh_.patches[patch];
  if (mesh_.emits(patch)) return options_.emitterSamples;
  if (options_.proximitySamples <= 0) return options_.shooterSamples;
  const double reach = p.diameter * std::sqrt(options_.proximitySamples / options_.shooterSamples);
  return proximityCount(p.diameter, nearestFacing(patch, reach));
}

int SampleCounter::operator()(const ShooterCluster& cluster) const {
  if (centroids().points().empty()) return kMaxClusterPoints;  // no distances to count by
  const double k = kClusterProximitySamples, D = cluster.diameter;
  const int fewest = options_.shooterSamples;
  const double nearest = nearestFacing(cluster, D * std::sqrt(k / fewest));
  if (!(nearest < HUGE_VAL)) return fewest;
  // Not capped at the emitters' count, as a patch's is: a cluster wanting more shoots as patches.
  const double wanted = std::ceil(k * (D / nearest) * (D / nearest) - 1e-9);
  return int(std::clamp<double>(wanted, fewest, kMaxClusterPoints));
}

double SampleCounter::nearestFacing(const ShooterCluster& c, double reach) const {
  std::array<glm::dvec3, 4> corners;
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (int k = 0; k < 4; ++k) {
    corners[k] = c.origin + (k & 1 ? c.uHi : c.uLo) * c.u + (k & 2 ? c.vHi : c.vLo) * c.v;
    lo = glm::min(lo, corners[k]);
    hi = glm::max(hi, corners[k]);
  }
  const PointTree& tree = centroids();
  const std::vector<glm::dvec3>& normal = normals();
  return tree.nearest(lo, hi, reach, [&](int e) {
    // An element in front of the plane that faces some point of the cluster's rectangle (a
    // corner, the rectangle being convex: a wall standing on the plane faces the part of it
    // before the wall), at its distance from the rectangle.
    const glm::dvec3& x = tree.points()[size_t(e)];
    const glm::dvec3 d = x - c.origin;
    if (glm::dot(d, c.normal) <= 1e-9 * c.diameter) return HUGE_VAL;
    bool facing = false;
    for (const glm::dvec3& corner : corners) facing = facing || glm::dot(x - corner, normal[size_t(e)]) < 0;
    if (!facing) return HUGE_VAL;
    const double a = std::clamp(glm::dot(d, c.u), c.uLo, c.uHi), b = std::clamp(glm::dot(d, c.v), c.vLo, c.vHi);
    return glm::length(x - (c.origin + a * c.u + b * c.v));
  });
}

namespace {

/// `count` stratified samples over the elements (of total `area`, in the plane of `normal`).
std::vector<ShooterSample> samplesOver(const PatchMesh& mesh, const std::vector<int>& elements, double area,
                                       const glm::dvec3& normal, int count) {
  std::vector<std::vector<Part>> strata;
  bisectByArea(elementParts(mesh, elements, area, count), count, strata);
  std::vector<ShooterSample> out;
  for (const auto& stratum : strata) {
    ShooterSample s;
    s.point = stratumPoint(stratum, normal);
    s.normal = normal;
    for (const Part& part : stratum) addShare(s, part);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

std::vector<ShooterSample> patchSamples(const PatchMesh& mesh, int patch, int count) {
  const Patch& p = mesh.patches[patch];
  return samplesOver(mesh, p.elements, p.area, p.normal, count);
}

std::vector<ShooterSample> clusterSamples(const PatchMesh& mesh, const ShooterCluster& cluster, int count) {
  return samplesOver(mesh, cluster.elements, cluster.area, cluster.normal, count);
}

}  // namespace rad
