#include "radiosity/true_error.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

#include "mesh/base/error.h"

namespace rad {
namespace {

/// Elements whose normal is farther than this from the point's are on another side.
constexpr double kFacing = 0.5;

/// The point of triangle (a, b, c) nearest x, as barycentric weights.
glm::dvec3 nearestWeights(const glm::dvec3& x, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double twice = glm::dot(n, n);
  glm::dvec3 w(glm::dot(glm::cross(c - b, x - b), n), glm::dot(glm::cross(a - c, x - c), n),
               glm::dot(glm::cross(b - a, x - a), n));
  w /= twice;
  if (w.x >= 0 && w.y >= 0 && w.z >= 0) return w;
  // Outside: the nearest point on the nearest edge.
  glm::dvec3 best(1, 0, 0);
  double bestDistance = HUGE_VAL;
  const glm::dvec3 corners[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 &p = corners[k], &q = corners[(k + 1) % 3];
    const double t = std::clamp(glm::dot(x - p, q - p) / glm::dot(q - p, q - p), 0.0, 1.0);
    const double d = glm::length(x - (p + t * (q - p)));
    if (d < bestDistance) {
      bestDistance = d;
      best = glm::dvec3(0.0);
      best[k] = 1 - t;
      best[(k + 1) % 3] = t;
    }
  }
  return best;
}

/// The relative errors (shown − reference) / reference over the points added, by channel
/// and by surface (in order of first appearance); channels of a reference below `floor` or
/// not above 0 are skipped.
class ErrorSums {
 public:
  explicit ErrorSums(const glm::dvec3& floor) : floor_(floor) {}

  /// Adds point `index`: reference p, `shown` there.
  void add(int index, const ReferencePoint& p, const glm::dvec3& shown) {
    auto [it, added] = surfaceIndex_.emplace(p.surface, s_.perSurface.size());
    if (added) s_.perSurface.push_back({p.surface, 0, 0, 0}), surfaceSq_.push_back(0), surfaceSum_.push_back(0);
    ++s_.perSurface[it->second].points;
    for (int c = 0; c < 3; ++c) addChannel(index, p, shown, c, it->second);
  }

  /// The summary of the points added.
  ErrorSummary summary() {
    for (int c = 0; c < 3; ++c)
      if (count_[c] > 0) s_.rmsRgb[c] = std::sqrt(sumSq_[c] / count_[c]), s_.meanRgb[c] = sum_[c] / count_[c];
    if (s_.used) s_.rms = std::sqrt(total_ / s_.used), s_.referenceNoise = std::sqrt(noise_ / s_.used);
    // Per surface, over the channels used there.
    for (size_t k = 0; k < s_.perSurface.size(); ++k) {
      const int used = s_.perSurface[k].channels;
      if (used) s_.perSurface[k].rms = std::sqrt(surfaceSq_[k] / used), s_.perSurface[k].mean = surfaceSum_[k] / used;
    }
    return s_;
  }

 private:
  void addChannel(int index, const ReferencePoint& p, const glm::dvec3& shown, int c, size_t surface) {
    if (!(p.B[c] > floor_[c]) || !(p.B[c] > 0)) {
      ++s_.skipped;
      return;
    }
    const double e = (shown[c] - p.B[c]) / p.B[c];
    ++s_.used;
    ++s_.perSurface[surface].channels;
    sum_[c] += e, sumSq_[c] += e * e, count_[c] += 1;
    total_ += e * e;
    noise_ += (p.standardError[c] / p.B[c]) * (p.standardError[c] / p.B[c]);
    surfaceSq_[surface] += e * e, surfaceSum_[surface] += e;
    if (std::abs(e) > std::abs(s_.worst)) s_.worst = e, s_.worstPoint = index, s_.worstShown = shown;
  }

  glm::dvec3 floor_;
  ErrorSummary s_;
  glm::dvec3 sumSq_{0.0}, sum_{0.0}, count_{0.0};
  double noise_ = 0, total_ = 0;
  std::map<std::string, size_t> surfaceIndex_;
  std::vector<double> surfaceSq_, surfaceSum_;
};

}  // namespace

TrueError::TrueError(const PatchMesh& mesh, const Scene& scene, std::vector<ReferencePoint> points,
                     const std::string& source)
    : points_(std::move(points)), where_(points_.size()) {
  std::map<std::string, int> surfaceOf;
  for (size_t s = 0; s < scene.surfaces.size(); ++s) surfaceOf.emplace(scene.surfaces[s].name, int(s));
  std::vector<std::vector<int>> elementsOf(scene.surfaces.size());
  for (int e = 0; e < mesh.elementCount(); ++e) elementsOf[size_t(mesh.surface(e))].push_back(e);
  const double reach = kOnResult * scene.diagonal();
  for (size_t i = 0; i < points_.size(); ++i) {
    const ReferencePoint& p = points_[i];
    const auto named = surfaceOf.find(p.surface);
    if (named == surfaceOf.end())
      throw inputError(source + ": point " + std::to_string(i + 1), "a surface of " + scene.path,
                       "'" + p.surface + "' (a reference of another scene?)");
    if (locate(mesh, elementsOf[size_t(named->second)], i) > reach) where_[i] = Location{}, ++notInResult_;
  }
  // The brightest lit value, emitters left out: a point on a lamp must not darken the rest.
  for (const auto& p : points_)
    if (!scene.materials[size_t(scene.surfaces[size_t(surfaceOf.at(p.surface))].material)].emits())
      floor_ = glm::max(floor_, p.B);
  floor_ *= kDarkShare;
}

double TrueError::locate(const PatchMesh& mesh, const std::vector<int>& candidates, size_t i) {
  const ReferencePoint& p = points_[i];
  double nearest = HUGE_VAL;
  for (int e : candidates) {
    if (glm::dot(mesh.normal(e), p.normal) < kFacing) continue;
    const auto c = mesh.corners(e);
    const glm::dvec3 w = nearestWeights(p.position, c[0], c[1], c[2]);
    const double d = glm::length(p.position - (w.x * c[0] + w.y * c[1] + w.z * c[2]));
    if (d >= nearest) continue;
    nearest = d;
    int k = 0;
    for (auto v : mesh.mesh.fv_range(TriMesh::FaceHandle(e))) where_[i].vertex[k++] = v.idx();
    where_[i].weight = w;
  }
  return nearest;
}

std::vector<glm::dvec3> TrueError::shown(const std::vector<glm::dvec3>& vertexValue) const {
  std::vector<glm::dvec3> out(points_.size(), glm::dvec3(0.0));
  for (size_t i = 0; i < points_.size(); ++i) {
    const Location& l = where_[i];
    if (l.vertex[0] < 0) continue;  // not in the result: nothing shown
    for (int k = 0; k < 3; ++k) out[i] += l.weight[k] * vertexValue[size_t(l.vertex[k])];
  }
  return out;
}

ErrorSummary TrueError::measure(const std::vector<glm::dvec3>& vertexValue) const {
  const std::vector<glm::dvec3> value = shown(vertexValue);
  ErrorSums sums(floor_);
  for (size_t i = 0; i < points_.size(); ++i) sums.add(int(i), points_[i], value[i]);
  return sums.summary();
}

}  // namespace rad
