// Scene or result ▸ camera: what the scene is (a closed room, an open box, an object), from
// rays out of its bounding box's centre, then the view that suits it (see the header).
#include "mesh/results/default_camera.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "mesh/base/color.h"
#include "mesh/scene/camera.h"
#include "mesh/scene/geometry.h"
#include "mesh/surface_rays.h"

namespace rad {
namespace {

/// Up, in every scene (the scene format has no other up).
const glm::dvec3 kUp(0, 1, 0);
/// Where the eye stands from an object's centre: raised, on the diagonal.
const glm::dvec3 kObjectSide(1, 0.6, 1);

/// An axis-aligned box.
struct Box {
  glm::dvec3 lo{HUGE_VAL}, hi{-HUGE_VAL};
  glm::dvec3 centre() const { return (lo + hi) * 0.5; }
};

/// A face of the bounding box thinner than this times its diagonal gets this thickness, so that
/// every ray from the centre has a direction.
constexpr double kMinBoxThickness = 1e-6;

/// The box of the polygons' outer rings, each side at least kMinBoxThickness of its diagonal.
Box boxOf(const std::vector<Polygon>& polygons) {
  Box box;
  for (const Polygon& polygon : polygons)
    for (const glm::dvec3& p : polygon.outer) box.lo = glm::min(box.lo, p), box.hi = glm::max(box.hi, p);
  const double thickness = std::max(kMinBoxThickness * glm::length(box.hi - box.lo), kPointBoxRadius);
  const glm::dvec3 grow = glm::max(glm::dvec3(thickness) - (box.hi - box.lo), glm::dvec3(0.0)) * 0.5;
  box.lo -= grow, box.hi += grow;
  return box;
}

/// The outward unit normal of the box's face `side` (0 to 5: +x, -x, +y, -y, +z, -z).
glm::dvec3 sideNormal(int side) {
  glm::dvec3 n(0.0);
  n[side / 2] = side % 2 ? -1 : 1;
  return n;
}

/// The point of the box's face `side` at fractions a and b along the face's two other axes.
glm::dvec3 facePoint(const Box& box, int side, double a, double b) {
  const int axis = side / 2, first = (axis + 1) % 3, second = (axis + 2) % 3;
  glm::dvec3 p;
  p[axis] = side % 2 ? box.lo[axis] : box.hi[axis];
  p[first] = glm::mix(box.lo[first], box.hi[first], a);
  p[second] = glm::mix(box.lo[second], box.hi[second], b);
  return p;
}

/// Rays per face of the bounding box: kFaceRays × kFaceRays, towards the middles of its cells.
constexpr int kFaceRays = 3;

/// Whether face `side` is open: most rays from the box's centre towards it, passing the backs of
/// one-sided surfaces, meet nothing.
bool sideOpen(const SurfaceRays& rays, const Box& box, int side) {
  int escaped = 0;
  for (int i = 0; i < kFaceRays; ++i)
    for (int j = 0; j < kFaceRays; ++j) {
      const glm::dvec3 towards = facePoint(box, side, (i + 0.5) / kFaceRays, (j + 0.5) / kFaceRays);
      if (!rays.firstHit(box.centre(), glm::normalize(towards - box.centre()), true)) ++escaped;
    }
  return 2 * escaped > kFaceRays * kFaceRays;
}

/// The open faces of the box, in side order.
std::vector<int> openSides(const SurfaceRays& rays, const Box& box) {
  std::vector<int> open;
  for (int side = 0; side < 6; ++side)
    if (sideOpen(rays, box, side)) open.push_back(side);
  return open;
}

/// Vertical field of view looking into an open box, degrees (as framingCamera's).
constexpr double kBoxFovDeg = 45;

/// Looking into the box through face `side`, from outside on the axis through its centre, at
/// the distance where the face fills a kBoxFovDeg view (square: the narrower of a wide picture).
Camera openBoxCamera(const Box& box, int side) {
  const glm::dvec3 out = sideNormal(side), extent = box.hi - box.lo;
  Camera c;
  c.fovYDeg = kBoxFovDeg;
  c.up = side / 2 == 1 ? glm::dvec3(0, 0, -1) : kUp;  // looking down or up: +z at the bottom
  const glm::dvec3 across = glm::cross(out, c.up);
  const double halfSize = 0.5 * std::max(std::abs(glm::dot(extent, c.up)), std::abs(glm::dot(extent, across)));
  const double distance = halfSize / std::tan(glm::radians(kBoxFovDeg) * 0.5);
  c.target = box.centre();
  c.eye = c.target + out * (0.5 * std::abs(glm::dot(extent, out)) + distance);
  return c;
}

/// Eye height above the floor, metres.
constexpr double kEyeHeightMetres = 1.6;
/// The eye stays at most this fraction of the room's height above its floor (a low room).
constexpr double kMaxEyeFraction = 0.8;
/// The eye's height as a fraction of the room's height when the units are unknown.
constexpr double kUnknownEyeFraction = 0.6;

/// The eye's height above the floor of a room `height` high (scene units).
double eyeHeight(double height, const std::optional<double>& unitsPerMetre) {
  if (!unitsPerMetre) return kUnknownEyeFraction * height;
  return std::min(kEyeHeightMetres * *unitsPerMetre, kMaxEyeFraction * height);
}

/// Whether a point is in open air: no ray from it sideways or up first meets the back of a surface.
bool inOpenAir(const SurfaceRays& rays, const glm::dvec3& p) {
  for (const glm::dvec3& dir : {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), kUp}) {
    const auto hit = rays.firstHit(p, dir, false);
    if (hit && !hit->front) return false;
  }
  return true;
}

/// How far below p its floor is: the lowest surface facing up under it (under a table's top, the
/// floor); nothing when there is none. `step` separates surfaces met at the same depth.
std::optional<double> floorDepth(const SurfaceRays& rays, const glm::dvec3& p, double step) {
  std::optional<double> depth;
  while (const auto hit = rays.firstHit(p, -kUp, true, depth ? *depth + step : 0)) depth = hit->t;
  return depth;
}

/// The eye of someone standing on the floor under p (at p's height or below it), when there is
/// a floor under p and a ceiling over it, nothing stands between the floor and the eye, and the
/// eye is in open air. `step`: a length far below any the scene draws.
std::optional<glm::dvec3> standingEye(const SurfaceRays& rays, const glm::dvec3& p, double step,
                                      const std::optional<double>& unitsPerMetre) {
  const auto floor = floorDepth(rays, p, step);
  const auto ceiling = rays.firstHit(p, kUp, true);
  if (!floor || !ceiling) return std::nullopt;
  const double height = eyeHeight(*floor + ceiling->t, unitsPerMetre);
  const glm::dvec3 eye = p - kUp * (*floor - height);
  const auto below = rays.firstHit(eye, -kUp, false);
  if (!below || !below->front || std::abs(below->t - height) > step || !inOpenAir(rays, eye)) return std::nullopt;
  return eye;
}

/// Standing points tried in a room: kFloorGrid × kFloorGrid over the box's floor plan.
constexpr int kFloorGrid = 11;
/// Surfaces met along a ray closer than this times the scene's diagonal count as one.
constexpr double kStep = 1e-9;

/// The eyes of the standing points over a grid across the box's floor plan, at its centre's height.
std::vector<glm::dvec3> standingEyes(const SurfaceRays& rays, const Box& box,
                                     const std::optional<double>& unitsPerMetre) {
  std::vector<glm::dvec3> eyes;
  for (int i = 0; i < kFloorGrid; ++i)
    for (int j = 0; j < kFloorGrid; ++j) {
      glm::dvec3 p = box.centre();
      p.x = glm::mix(box.lo.x, box.hi.x, (i + 0.5) / kFloorGrid);
      p.z = glm::mix(box.lo.z, box.hi.z, (j + 0.5) / kFloorGrid);
      if (const auto eye = standingEye(rays, p, kStep * glm::length(box.hi - box.lo), unitsPerMetre))
        eyes.push_back(*eye);
    }
  return eyes;
}

/// The eye nearest (across the floor) to the middle of all of them (not empty); the first of equals.
glm::dvec3 middleEye(const std::vector<glm::dvec3>& eyes) {
  glm::dvec3 middle(0.0);
  for (const glm::dvec3& eye : eyes) middle += eye / double(eyes.size());
  const auto across = [&](const glm::dvec3& eye) { return glm::length(glm::dvec2(eye.x - middle.x, eye.z - middle.z)); };
  return *std::min_element(eyes.begin(), eyes.end(),
                           [&](const glm::dvec3& a, const glm::dvec3& b) { return across(a) < across(b); });
}

/// Horizontal directions tried for the deepest view, evenly spread from +x.
constexpr int kViewDirections = 8;

/// The horizontal direction from the eye that sees farthest before meeting a surface.
glm::dvec3 deepestView(const SurfaceRays& rays, const glm::dvec3& eye) {
  glm::dvec3 deepest(1, 0, 0);
  double depth = -1;
  for (int k = 0; k < kViewDirections; ++k) {
    const double angle = 2 * M_PI * k / kViewDirections;
    const glm::dvec3 dir(std::cos(angle), 0, std::sin(angle));
    const auto hit = rays.firstHit(eye, dir, false);
    const double t = hit ? hit->t : HUGE_VAL;
    if (t > depth) depth = t, deepest = dir;
  }
  return deepest;
}

/// Horizontally towards the light, unless it is more than 45° overhead (or there is none): then
/// the deepest view.
glm::dvec3 roomView(const SurfaceRays& rays, const glm::dvec3& eye, const std::optional<glm::dvec3>& light) {
  if (light) {
    const glm::dvec3 towards = *light - eye;
    const glm::dvec3 level = towards - kUp * glm::dot(towards, kUp);
    if (glm::length(level) > 0 && glm::length(level) >= glm::dot(towards, kUp)) return glm::normalize(level);
  }
  return deepestView(rays, eye);
}

/// Vertical field of view inside a room, degrees: wide enough to see a corner of it.
constexpr double kRoomFovDeg = 60;

/// Standing in the room at eye height, in the middle of its free floor, looking horizontally at
/// the light; nothing when no point of the floor plan is free.
std::optional<Camera> roomCamera(const ViewGeometry& g, const SurfaceRays& rays, const Box& box) {
  const std::vector<glm::dvec3> eyes = standingEyes(rays, box, g.unitsPerMetre);
  if (eyes.empty()) return std::nullopt;
  Camera c;
  c.fovYDeg = kRoomFovDeg;
  c.eye = middleEye(eyes);
  c.target = c.eye + roomView(rays, c.eye, g.light) * (0.25 * glm::length(box.hi - box.lo));
  c.up = kUp;
  return c;
}

/// The area and the area-weighted centre of polygons (each at the mean of its outer ring).
std::pair<double, glm::dvec3> areaCentre(const std::vector<Polygon>& polygons) {
  double area = 0;
  glm::dvec3 weighted(0.0);
  for (const Polygon& polygon : polygons) {
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& p : polygon.outer) mean += p / double(polygon.outer.size());
    area += polygonArea(polygon);
    weighted += polygonArea(polygon) * mean;
  }
  return {area, area > 0 ? weighted / area : weighted};
}

/// A result face as a polygon.
Polygon facePolygon(const ResultFile& result, size_t face) {
  Polygon polygon;
  for (int v : result.faces[face]) polygon.outer.push_back(glm::dvec3(result.positions[size_t(v)]));
  return polygon;
}

/// A result's faces at least this fraction of the brightest face's luminance make its light.
constexpr double kLitFraction = 0.5;

/// The result's most lit part: the faces of the brightest face's surface at least kLitFraction
/// as bright as it, at their area-weighted centre; nothing when every face is dark.
std::optional<glm::dvec3> brightestPart(const ResultFile& result, const std::vector<Polygon>& faces) {
  std::vector<double> shown(result.faceRadiosity.size());
  for (size_t f = 0; f < shown.size(); ++f) shown[f] = luminance(result.faceRadiosity[f]);
  const auto brightest = std::max_element(shown.begin(), shown.end());
  if (brightest == shown.end() || !(*brightest > 0)) return std::nullopt;
  const size_t first = size_t(brightest - shown.begin());
  std::vector<Polygon> lit;
  for (size_t f = 0; f < shown.size(); ++f)
    if (shown[f] >= kLitFraction * *brightest &&
        (result.faceSurface.empty() || result.faceSurface[f] == result.faceSurface[first]))
      lit.push_back(faces[f]);
  return areaCentre(lit).second;
}

}  // namespace

std::optional<double> unitsPerMetre(const std::string& units) {
  static const std::map<std::string, double> kPerMetre = {
      {"mm", 1000}, {"millimetre", 1000}, {"millimeter", 1000}, {"cm", 100}, {"centimetre", 100},
      {"centimeter", 100}, {"dm", 10}, {"decimetre", 10}, {"decimeter", 10}, {"m", 1}, {"metre", 1},
      {"meter", 1}, {"km", 1e-3}, {"kilometre", 1e-3}, {"kilometer", 1e-3}, {"in", 1 / 0.0254},
      {"inch", 1 / 0.0254}, {"inches", 1 / 0.0254}, {"ft", 1 / 0.3048}, {"foot", 1 / 0.3048},
      {"feet", 1 / 0.3048}, {"yd", 1 / 0.9144}, {"yard", 1 / 0.9144}};
  std::string name;
  for (char ch : units) name += char(std::tolower(static_cast<unsigned char>(ch)));
  if (!kPerMetre.count(name) && name.size() > 3 && name.back() == 's') name.pop_back();  // "metres"
  const auto found = kPerMetre.find(name);
  if (found == kPerMetre.end()) return std::nullopt;
  return found->second;
}

ViewGeometry viewGeometry(const Scene& scene) {
  ViewGeometry g;
  g.unitsPerMetre = unitsPerMetre(scene.units);
  double mostPower = 0;
  for (const Surface& surface : scene.surfaces) {
    g.polygons.insert(g.polygons.end(), surface.polygons.begin(), surface.polygons.end());
    g.twoSided.insert(g.twoSided.end(), surface.polygons.size(), surface.twoSided);
    const double exitance = luminance(scene.materials[size_t(surface.material)].emission);
    if (!(exitance > 0)) continue;
    const auto [area, centre] = areaCentre(surface.polygons);
    if (exitance * area > mostPower) mostPower = exitance * area, g.light = centre;
  }
  return g;
}

ViewGeometry viewGeometry(const ResultFile& result) {
  ViewGeometry g;
  for (size_t f = 0; f < result.faces.size(); ++f) g.polygons.push_back(facePolygon(result, f));
  g.twoSided.assign(g.polygons.size(), false);
  g.light = brightestPart(result, g.polygons);
  return g;
}

Camera defaultCamera(const ViewGeometry& g) {
  const Box box = boxOf(g.polygons);
  const SurfaceRays rays(g.polygons, g.twoSided);
  const std::vector<int> open = openSides(rays, box);
  if (open.empty())
    if (const auto room = roomCamera(g, rays, box)) return *room;
  if (open.size() == 1) return openBoxCamera(box, open[0]);
  return framingCamera(box.lo, box.hi, kObjectSide);
}

Camera defaultCamera(const Scene& scene) { return defaultCamera(viewGeometry(scene)); }

Camera defaultCamera(const ResultFile& result) {
  if (result.faces.empty()) return defaultCamera(result.boundsMin, result.boundsMax);
  return defaultCamera(viewGeometry(result));
}

}  // namespace rad
