// Emitters ▸ light paths ▸ which side of each face the lit space sees ▸ sheets turned round.
#include "mesh/facing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>

#include <glm/geometric.hpp>

#include "mesh/base/number_text.h"
#include "mesh/base/parallel.h"
#include "mesh/base/union_find.h"
#include "mesh/scene/geometry.h"
#include "mesh/surface_rays.h"

namespace rad {
namespace {

/// The paths' seed: fixed, not the solver's, so that every command turns the same faces.
constexpr unsigned kSeed = 1;
/// Tries at drawing a point inside a polygon from its box before the path is given up.
constexpr int kPointTries = 32;

/// splitmix64's finaliser: a well-mixed 64-bit value of x.
uint64_t mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// A path's own random numbers in [0, 1): splitmix64 from a state mixed from (seed, path), so
/// that a path is the same whichever worker follows it, and neighbouring paths' streams are not
/// each other's shifted by a draw (as a sum of the path index would make them).
class PathRandom {
 public:
  PathRandom(unsigned seed, size_t path) : state_(mix(mix(uint64_t(seed)) ^ uint64_t(path))) {}
  double next() { return double(mix(state_ += 0x9E3779B97F4A7C15ull) >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

/// A cosine-spread direction about the unit normal n (Malley's method).
glm::dvec3 cosineDirection(const glm::dvec3& n, PathRandom& random) {
  const double u = random.next();
  const double phi = 2 * M_PI * random.next();
  const double r = std::sqrt(u);
  const PlaneFrame frame = planeFrame(glm::dvec3(0.0), n);
  return glm::normalize(frame.u * (r * std::cos(phi)) + frame.v * (r * std::sin(phi)) + n * std::sqrt(1 - u));
}

/// Every polygon of the scene, surface by surface, with its surface and its plane.
struct ScenePolygons {
  std::vector<Polygon> polygons;
  std::vector<int> surface;
  std::vector<bool> twoSided;
  std::vector<PlaneFrame> frames;

  explicit ScenePolygons(const Scene& scene) {
    for (size_t s = 0; s < scene.surfaces.size(); ++s)
      for (const Polygon& polygon : scene.surfaces[s].polygons) {
        polygons.push_back(polygon);
        surface.push_back(int(s));
        twoSided.push_back(scene.surfaces[s].twoSided);
        frames.push_back(planeFrame(polygon.outer));
      }
  }
};

/// The emitting polygons and their running areas, to pick a start in proportion to area.
struct Emitters {
  std::vector<int> polygon;
  std::vector<double> runningArea;

  Emitters(const Scene& scene, const ScenePolygons& all) {
    double total = 0;
    for (size_t i = 0; i < all.polygons.size(); ++i) {
      const Surface& surface = scene.surfaces[size_t(all.surface[i])];
      if (!scene.materials[size_t(surface.material)].emits()) continue;
      const double area = polygonArea(all.polygons[i]);
      if (!(area > 0)) continue;
      polygon.push_back(int(i));
      runningArea.push_back(total += area);
    }
  }
  int pick(double u) const {
    const auto at = std::upper_bound(runningArea.begin(), runningArea.end(), u * runningArea.back());
    return polygon[std::min<size_t>(size_t(at - runningArea.begin()), polygon.size() - 1)];
  }
};

/// A point of the polygon drawn uniformly (rejection from its box in its plane), if one of
/// kPointTries draws falls inside.
std::optional<glm::dvec3> pointOn(const Polygon& polygon, const PlaneFrame& frame, PathRandom& random) {
  glm::dvec2 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const glm::dvec3& p : polygon.outer) {
    const glm::dvec2 q = frame.project(p);
    lo = glm::min(lo, q), hi = glm::max(hi, q);
  }
  for (int attempt = 0; attempt < kPointTries; ++attempt) {
    const double a = random.next(), b = random.next();
    const glm::dvec3 p = frame.lift(lo + (hi - lo) * glm::dvec2(a, b));
    if (insidePolygon(frame, polygon, p)) return p;
  }
  return std::nullopt;
}

/// Follows one light path, counting the sides it meets (`front`, `back` per polygon). A path ends
/// on the back of a one-sided surface, which absorbs it: a path that slips into a closed object
/// through a seam meets one of its backs once, not at every bounce inside.
void followPath(const ScenePolygons& all, const SurfaceRays& rays, const Emitters& emitters, double offset,
                PathRandom& random, std::vector<SideHits>& hits) {
  const int start = emitters.pick(random.next());
  const std::optional<glm::dvec3> origin = pointOn(all.polygons[size_t(start)], all.frames[size_t(start)], random);
  if (!origin) return;
  glm::dvec3 normal = all.frames[size_t(start)].normal;
  if (all.twoSided[size_t(start)] && random.next() < 0.5) normal = -normal;
  glm::dvec3 p = *origin;
  for (int bounce = 0; bounce <= kFacingBounces; ++bounce) {
    const glm::dvec3 from = p + normal * offset;
    const glm::dvec3 dir = cosineDirection(normal, random);
    const std::optional<RayHit> hit = rays.firstHit(from, dir, false);
    if (!hit) return;
    const size_t i = size_t(hit->polygon);
    const glm::dvec3 n = all.frames[i].normal;
    const bool front = glm::dot(dir, n) < 0;  // met on the side its normal points to
    (front || all.twoSided[i] ? hits[i].front : hits[i].back) += 1;
    if (!front && !all.twoSided[i]) return;
    p = from + dir * hit->t;
    normal = front ? n : -n;
  }
}

/// The polygons of a surface grouped into consistently wound sheets: two polygons belong together
/// when they share an edge that they run along in opposite directions (their windings agree
/// across it). Each polygon's sheet, as the index of one of its polygons.
std::vector<size_t> windingSheets(const Surface& surface) {
  std::map<std::array<double, 3>, int> ids;
  auto id = [&](const glm::dvec3& p) {
    return ids.emplace(std::array<double, 3>{p.x, p.y, p.z}, int(ids.size())).first->second;
  };
  std::map<std::pair<int, int>, std::vector<size_t>> along;  // directed edge → the polygons running along it
  const std::vector<Polygon>& polygons = surface.polygons;
  for (size_t k = 0; k < polygons.size(); ++k) {
    const Ring& ring = polygons[k].outer;
    for (size_t i = 0; i < ring.size(); ++i) along[{id(ring[i]), id(ring[(i + 1) % ring.size()])}].push_back(k);
  }
  UnionFind sheets(polygons.size());
  for (const auto& [edge, list] : along)
    if (const auto twin = along.find({edge.second, edge.first}); twin != along.end())
      for (size_t k : list)
        for (size_t j : twin->second) sheets.join(k, j);
  std::vector<size_t> sheet(polygons.size());
  for (size_t k = 0; k < polygons.size(); ++k) sheet[k] = sheets.find(k);
  return sheet;
}

/// A polygon turned round: its rings wound the other way.
void turnRound(Polygon& polygon) {
  std::reverse(polygon.outer.begin(), polygon.outer.end());
  for (Ring& hole : polygon.holes) std::reverse(hole.begin(), hole.end());
}

/// What was turned of one surface.
struct Turned {
  int faces = 0;
  double area = 0;
  SideHits hits;  ///< the turned faces' hits, as met before turning
};

/// Whether a sheet met so is turned round.
bool facesAway(const SideHits& h) { return h.back > kFacingMinHits && double(h.back) >= kFacingBackRatio * double(h.front); }

/// Turns round every sheet of a one-sided mesh-file surface that light meets mostly on its back;
/// `hits` holds its polygons' counts.
Turned turnSheets(Surface& surface, const SideHits* hits) {
  const std::vector<size_t> sheet = windingSheets(surface);
  std::map<size_t, SideHits> bySheet;
  for (size_t k = 0; k < sheet.size(); ++k)
    bySheet[sheet[k]].front += hits[k].front, bySheet[sheet[k]].back += hits[k].back;
  Turned turned;
  for (size_t k = 0; k < sheet.size(); ++k) {
    if (!facesAway(bySheet[sheet[k]])) continue;
    turnRound(surface.polygons[k]);
    turned.faces += 1;
    turned.area += polygonArea(surface.polygons[k]);
    turned.hits.front += hits[k].front, turned.hits.back += hits[k].back;
  }
  return turned;
}

/// The warning for a surface some or all of whose faces were turned round.
std::string turnedWarning(const Scene& scene, const Surface& surface, const Turned& t) {
  double area = 0;
  for (const Polygon& polygon : surface.polygons) area += polygonArea(polygon);
  const std::string faces = t.faces == int(surface.polygons.size())
                                ? "all " + std::to_string(t.faces) + " of its faces"
                                : formatted("%d of its %zu faces", t.faces, surface.polygons.size());
  return surface.where + ": surface '" + surface.name + "' (" + scene.materials[size_t(surface.material)].name +
         ") faces away from the light: " + faces + formatted(" (area %.4g of %.4g)", t.area, area) +
         formatted(", which light paths from the emitters met %ld times on their backs and %ld on their fronts, "
                   "were turned round (to keep the file's facing, set solver.fix_facing to false)",
                   t.hits.back, t.hits.front);
}

}  // namespace

std::vector<SideHits> litSpaceHits(const Scene& scene) {
  const ScenePolygons all(scene);
  std::vector<SideHits> total(all.polygons.size());
  const Emitters emitters(scene, all);
  if (emitters.polygon.empty()) return total;
  const SurfaceRays rays(all.polygons, all.twoSided);
  const double offset = 1e-7 * scene.diagonal();
  const int workers = workerCount();
  std::vector<std::vector<SideHits>> hits(size_t(workers), std::vector<SideHits>(all.polygons.size()));
  parallelFor(
      kFacingPaths, workers,
      [&](size_t path, int worker) {
        PathRandom random(kSeed, path);
        followPath(all, rays, emitters, offset, random, hits[size_t(worker)]);
      },
      256);
  for (const auto& counts : hits)
    for (size_t i = 0; i < counts.size(); ++i) total[i].front += counts[i].front, total[i].back += counts[i].back;
  return total;
}

FacingRepair turnToLitSpace(Scene& scene) {
  FacingRepair repair;
  const std::vector<SideHits> hits = litSpaceHits(scene);
  size_t first = 0;  // the surface's first polygon in `hits`
  for (size_t s = 0; s < scene.surfaces.size(); first += scene.surfaces[s].polygons.size(), ++s) {
    Surface& surface = scene.surfaces[s];
    if (!surface.fromMeshFile || surface.twoSided) continue;
    const Turned turned = turnSheets(surface, hits.data() + first);
    if (turned.faces == 0) continue;
    repair.turned.push_back(int(s));
    repair.turnedFaces += turned.faces;
    repair.warnings.push_back(turnedWarning(scene, surface, turned));
  }
  return repair;
}

}  // namespace rad
