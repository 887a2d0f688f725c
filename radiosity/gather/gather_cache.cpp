#include "radiosity/gather/gather_cache.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "radiosity/light/direct_light.h"

namespace rad {
namespace {

/// The levels after which every vertex still uncovered gathers: cells of 2⁻²⁰ of the first
/// level's are finer than any mesh's vertices.
constexpr int kMaxLevels = 20;
/// A point lies in front of a gathering vertex when it is this share of R behind its plane
/// (Ward's tolerance).
constexpr double kInFrontOfReach = 0.05;

/// A vertex as the choice sees it.
struct Site {
  glm::dvec3 p, n;
  int surface = -1;
  /// On a contact line: the light changes across it, and vertices at the same place on its
  /// two sides see different rooms, so it gathers itself and no other takes its light.
  bool seam = false;
  /// On its surface's outline (where another surface meets it, or at a crease): it gathers
  /// itself, as what lies beyond the outline is what its neighbours inside do not see.
  bool outline = false;
};

/// Integer cell coordinates of p on a grid of cell `size`, with the surface, as a hash key.
struct Cell {
  int64_t x, y, z;
  int surface;
  bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z && surface == o.surface; }
};
struct CellHash {
  size_t operator()(const Cell& c) const {
    uint64_t h = uint64_t(c.x) * 0x9e3779b97f4a7c15ull;
    h ^= uint64_t(c.y) * 0xc2b2ae3d27d4eb4full + (h << 6) + (h >> 2);
    h ^= uint64_t(c.z) * 0x165667b19e3779f9ull + (h << 6) + (h >> 2);
    h ^= uint64_t(uint32_t(c.surface)) * 0x27d4eb2f165667c5ull + (h << 6) + (h >> 2);
    return size_t(h);
  }
};

Cell cellOf(const glm::dvec3& p, double size, int surface) {
  return {int64_t(std::floor(p.x / size)), int64_t(std::floor(p.y / size)), int64_t(std::floor(p.z / size)), surface};
}

/// Grids of cells halving in size: a reach goes to the finest whose cells are as wide as it.
constexpr int kReachGrids = 48;

/// The gathering vertices found so far, each listed in the cells its reach (accuracy·R)
/// overlaps on the grid as fine as that reach (at most eight): a dense model's gathering
/// vertices, whose reaches are small, share no list with the room's.
class Gathered {
 public:
  Gathered(double cell, double accuracy) : cell_(cell), accuracy_(accuracy) {}

  void add(int v, const Site& s, double R) {
    const double r = accuracy_ * R;
    int grid = 0;
    while (grid + 1 < kReachGrids && r <= size(grid + 1)) ++grid;
    finest_ = std::max(finest_, grid);
    const Cell lo = cellOf(s.p - glm::dvec3(r), size(grid), s.surface);
    const Cell hi = cellOf(s.p + glm::dvec3(r), size(grid), s.surface);
    for (int64_t x = lo.x; x <= hi.x; ++x)
      for (int64_t y = lo.y; y <= hi.y; ++y)
        for (int64_t z = lo.z; z <= hi.z; ++z) cells_[size_t(grid)][{x, y, z, s.surface}].push_back(v);
  }
  /// Calls f with each gathering vertex whose reach may cover site s.
  template <class F>
  void near(const Site& s, F f) const {
    for (int grid = 0; grid <= finest_; ++grid) {
      const auto& cells = cells_[size_t(grid)];
      if (cells.empty()) continue;
      const auto it = cells.find(cellOf(s.p, size(grid), s.surface));
      if (it != cells.end())
        for (int g : it->second) f(g);
    }
  }

 private:
  double size(int grid) const { return std::ldexp(cell_, -grid); }
  double cell_, accuracy_;
  int finest_ = 0;
  std::array<std::unordered_map<Cell, std::vector<int>, CellHash>, kReachGrids> cells_;
};

}  // namespace

double gatherWeight(const glm::dvec3& p, const glm::dvec3& n, double R, const glm::dvec3& q, const glm::dvec3& m,
                    double accuracy) {
  if (R <= 0) return 0;
  const glm::dvec3 d = q - p;
  if (glm::dot(d, 0.5 * (n + m)) < -kInFrontOfReach * R) return 0;
  const double epsilon = glm::length(d) / R + std::sqrt(std::max(0.0, 1 - glm::dot(n, m)));
  if (epsilon >= accuracy) return 0;
  return 1 / std::max(epsilon, std::numeric_limits<double>::min()) - 1 / accuracy;
}

double maxGatherReach(double sceneSize, double accuracy, double farthest) {
  const double reach = kMaxGatherReach * sceneSize;
  return farthest > 0 && accuracy > 0 ? std::min(reach, farthest / accuracy) : reach;
}

GatherCache chooseGathering(const PatchMesh& mesh, const std::vector<int>& candidates, double accuracy,
                            double sceneSize, double farthest, const GatherRender& render) {
  const size_t n = mesh.mesh.n_vertices();
  GatherCache out;
  out.from.resize(n);
  out.reach.assign(n, 0.0);
  std::vector<double> nearest(n, 0.0);
  auto gathers = [&](int v) {
    out.from[size_t(v)] = {{v, 1.0}};
    ++out.gathering;
  };
  if (accuracy <= 0) {
    out.levels = 1;
    if (!render(candidates, nearest)) return GatherCache{{}, {}, 0, 1, false};
    for (int v : candidates) gathers(v);
    return out;
  }
  std::vector<Site> sites(n);
  for (int v : candidates) {
    const TriMesh::VertexHandle h(v);
    Site& s = sites[size_t(v)];
    const DirectLight::Probe probe = vertexProbe(mesh, h);
    s.p = offSurface(probe, sceneSize);  // where its hemicube looks from
    s.n = probe.normal;
    s.seam = mesh.seam(h);
    s.outline = mesh.mesh.is_boundary(h);
    for (auto f : mesh.mesh.vf_range(h)) {
      s.surface = mesh.surface(f.idx());
      break;
    }
  }
  const double maxReach = maxGatherReach(sceneSize, accuracy, farthest);
  Gathered gathered(accuracy * maxReach, accuracy);
  auto covered = [&](int v) {
    bool any = false;
    gathered.near(sites[size_t(v)], [&](int g) {
      any = any || gatherWeight(sites[size_t(g)].p, sites[size_t(g)].n, out.reach[size_t(g)], sites[size_t(v)].p,
                                sites[size_t(v)].n, accuracy) > 0;
    });
    return any;
  };
  std::vector<int> uncovered = candidates;
  double cell = kFirstGatherCell * sceneSize;
  for (; !uncovered.empty(); ++out.levels, cell /= 2) {
    // One vertex per cell and surface, the nearest the cell's centre (of two, the lower).
    std::vector<int> chosen;
    if (out.levels + 1 >= kMaxLevels) {
      chosen = uncovered;
    } else {
      std::unordered_map<Cell, int, CellHash> best;
      auto distance = [&](int v) {
        const Cell c = cellOf(sites[size_t(v)].p, cell, sites[size_t(v)].surface);
        const glm::dvec3 centre = (glm::dvec3(double(c.x), double(c.y), double(c.z)) + 0.5) * cell;
        return glm::length(sites[size_t(v)].p - centre);
      };
      for (int v : uncovered) {
        if (sites[size_t(v)].seam || sites[size_t(v)].outline) {
          chosen.push_back(v);
          continue;
        }
        auto [it, added] = best.try_emplace(cellOf(sites[size_t(v)].p, cell, sites[size_t(v)].surface), v);
        if (!added && distance(v) < distance(it->second)) it->second = v;
      }
      for (const auto& [c, v] : best) chosen.push_back(v);
      std::sort(chosen.begin(), chosen.end());
    }
    if (!render(chosen, nearest)) return GatherCache{{}, {}, 0, out.levels + 1, false};
    for (int v : chosen) {
      out.reach[size_t(v)] = std::min(nearest[size_t(v)], maxReach);
      if (!sites[size_t(v)].seam) gathered.add(v, sites[size_t(v)], out.reach[size_t(v)]);
      gathers(v);
    }
    std::vector<int> left;
    for (int v : uncovered)
      if (out.from[size_t(v)].empty() && !covered(v)) left.push_back(v);
    uncovered = std::move(left);
  }
  // Each vertex that does not gather: Ward's weighted mean of the gathering ones covering it.
  for (int v : candidates) {
    if (!out.from[size_t(v)].empty()) continue;
    const Site& s = sites[size_t(v)];
    double sum = 0;
    gathered.near(s, [&](int g) {
      const double w = gatherWeight(sites[size_t(g)].p, sites[size_t(g)].n, out.reach[size_t(g)], s.p, s.n, accuracy);
      if (w > 0) out.from[size_t(v)].emplace_back(g, w), sum += w;
    });
    for (auto& [g, w] : out.from[size_t(v)]) w /= sum;
  }
  return out;
}

std::vector<int> disagreeing(const GatherCache& cache, const std::function<double(int)>& light, double agreement) {
  std::vector<int> out;
  if (agreement <= 0) return out;
  std::vector<double> known(cache.from.size(), -1.0);  // light per gathering vertex, once asked
  for (size_t v = 0; v < cache.from.size(); ++v) {
    const auto& from = cache.from[v];
    if (from.empty() || (from.size() == 1 && from[0].first == int(v))) continue;  // not asked, or gathers
    if (from.size() == 1) {
      out.push_back(int(v));
      continue;
    }
    double lo = HUGE_VAL, hi = 0, mean = 0;
    for (const auto& [g, w] : from) {
      double& h = known[size_t(g)];
      if (h < 0) h = light(g);
      lo = std::min(lo, h), hi = std::max(hi, h), mean += w * h;
    }
    if (hi - lo > agreement * mean) out.push_back(int(v));
  }
  return out;
}

}  // namespace rad
