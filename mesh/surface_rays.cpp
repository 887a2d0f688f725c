// Polygons ▸ rays: Embree, in single precision, finds the polygons whose boxes a ray crosses,
// each box widened so that the float ray enters every box its double ray enters; each polygon
// is then met or missed in double precision, where the ray crosses its plane inside its rings
// (even-odd). The hit is the one a test of every polygon would find.
#include "mesh/surface_rays.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <embree3/rtcore.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "mesh/scene/geometry.h"

namespace rad {
namespace {

/// A polygon's box is widened by this times its size plus its distance from the origin, so that
/// round-off in a hit point (a flat box for a polygon along an axis) does not lose the hit.
constexpr double kBoxSlack = 1e-9;
/// Embree's boxes reach beyond the polygons' by this times the scene's reach (its largest
/// coordinate plus its diagonal). A float ray strays from its double ray by about 2⁻²⁴ ≈ 6e-8
/// of that (its origin's round-off, and its direction's times a distance across the scene), so
/// it enters every box the double ray enters, with room to spare; Embree's robust traversal
/// rounds its own box tests outward.
constexpr double kFloatSlack = 1e-6;

/// Even-odd over the outer ring and the holes: whether p, on the frame's plane, is inside.
bool insidePolygon(const PlaneFrame& frame, const Polygon& polygon, const glm::dvec3& p) {
  bool inside = insideRing(frame, polygon.outer, p);
  for (const Ring& hole : polygon.holes) inside = inside != insideRing(frame, hole, p);
  return inside;
}

/// The float nearest x from below, and from above.
float floatBelow(double x) {
  const float f = float(x);
  return double(f) > x ? std::nextafter(f, -HUGE_VALF) : f;
}
float floatAbove(double x) {
  const float f = float(x);
  return double(f) < x ? std::nextafter(f, HUGE_VALF) : f;
}

/// Whether meeting polygon i at t comes before `best`: nearer, or as near and given first, so
/// that the hit does not hang on the order Embree visits the boxes in.
bool before(double t, int i, const std::optional<RayHit>& best) {
  if (!best) return t < HUGE_VAL;
  return t < best->t || (t == best->t && i < best->polygon);
}

}  // namespace

struct SurfaceRays::Scene {
  /// A polygon as the rays test it.
  struct Target {
    PlaneFrame frame;   ///< a zero normal for a zero-area polygon
    glm::dvec3 lo, hi;  ///< the polygon's box, widened by round-off
    bool twoSided = false;
  };
  /// A ray as the search carries it.
  struct Ray {
    glm::dvec3 origin, dir;
    bool throughBacks = false;
    double after = 0;
  };
  /// What Embree hands the intersect callback with each ray: the double ray and the best hit so
  /// far, so that rays from several threads share nothing but the scene.
  struct Context : RTCIntersectContext {
    const Scene* scene = nullptr;
    Ray ray;
    double start = 0;  ///< where along `ray` Embree's float ray starts
    std::optional<RayHit> best;
  };

  Scene(const std::vector<Polygon>& polygons, const std::vector<bool>& twoSided);
  ~Scene();

  static Target target(const Polygon& polygon, bool twoSided);
  void build();
  static void bounds(const RTCBoundsFunctionArguments* args);
  static void intersect(const RTCIntersectFunctionNArguments* args);
  std::pair<double, double> crossing(const Ray& ray) const;
  std::optional<RayHit> firstHit(const Ray& ray) const;
  bool meets(int i, const Ray& ray, const std::optional<RayHit>& best, double& t) const;
  RayHit hit(int i, const Ray& ray, double t) const;

  const std::vector<Polygon>& polygons;
  std::vector<Target> targets;
  glm::dvec3 lo{HUGE_VAL}, hi{-HUGE_VAL};  ///< round every target, widened by `slack`
  double slack = 0;                        ///< how far Embree's boxes reach beyond the targets'
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

SurfaceRays::Scene::Scene(const std::vector<Polygon>& polygons, const std::vector<bool>& twoSided)
    : polygons(polygons) {
  for (size_t i = 0; i < polygons.size(); ++i) targets.push_back(target(polygons[i], twoSided[i]));
  for (const Target& t : targets) lo = glm::min(lo, t.lo), hi = glm::max(hi, t.hi);
  const glm::dvec3 far = glm::max(glm::abs(lo), glm::abs(hi));
  slack = kFloatSlack * (std::max({far.x, far.y, far.z}) + glm::length(hi - lo));
  lo -= glm::dvec3(slack), hi += glm::dvec3(slack);
  build();
}

SurfaceRays::Scene::~Scene() {
  if (scene) rtcReleaseScene(scene);
  if (device) rtcReleaseDevice(device);
}

SurfaceRays::Scene::Target SurfaceRays::Scene::target(const Polygon& polygon, bool twoSided) {
  Target target{planeFrame(polygon.outer), glm::dvec3(HUGE_VAL), glm::dvec3(-HUGE_VAL), twoSided};
  for (const glm::dvec3& p : polygon.outer) target.lo = glm::min(target.lo, p), target.hi = glm::max(target.hi, p);
  const double size = glm::length(target.hi - target.lo);
  const double reach = size + glm::length(glm::max(glm::abs(target.lo), glm::abs(target.hi)));
  target.lo -= glm::dvec3(kBoxSlack * reach), target.hi += glm::dvec3(kBoxSlack * reach);
  if (glm::length(newellNormal(polygon.outer)) <= kMinRelativeArea * size * size)
    target.frame.normal = glm::dvec3(0.0);  // never met
  return target;
}

/// One user primitive per polygon: Embree asks for its box and leaves meeting it to the
/// callback.
void SurfaceRays::Scene::build() {
  device = rtcNewDevice(nullptr);
  scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, unsigned(targets.size()));
  rtcSetGeometryUserData(geometry, this);
  rtcSetGeometryBoundsFunction(geometry, bounds, this);
  rtcSetGeometryIntersectFunction(geometry, intersect);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("embree: scene build failed");
}

/// Embree's box of a polygon: its box widened by the slack, rounded outward to float.
void SurfaceRays::Scene::bounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = *static_cast<const Scene*>(args->geometryUserPtr);
  const Target& target = s.targets[args->primID];
  const glm::dvec3 lo = target.lo - s.slack, hi = target.hi + s.slack;
  RTCBounds& b = *args->bounds_o;
  b.lower_x = floatBelow(lo.x), b.lower_y = floatBelow(lo.y), b.lower_z = floatBelow(lo.z);
  b.upper_x = floatAbove(hi.x), b.upper_y = floatAbove(hi.y), b.upper_z = floatAbove(hi.z);
}

/// Meets the polygon whose box Embree's ray entered with the double ray; a better hit moves
/// Embree's far end to it, rounded up, so that boxes beyond it are skipped but not those as
/// near (a tie may still win by its index).
void SurfaceRays::Scene::intersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto& context = *static_cast<Context*>(args->context);
  const int i = int(args->primID);
  double t = 0;
  if (!context.scene->meets(i, context.ray, context.best, t)) return;
  context.best = context.scene->hit(i, context.ray, t);
  RTCRayN_tfar(RTCRayHitN_RayN(args->rayhit, args->N), args->N, 0) = floatAbove(t - context.start);
}

/// The distances along the ray at which it enters the scene's box (0 at the earliest) and
/// leaves it: in after out when it misses. An axis the ray does not move along is tested apart,
/// where 0 · ∞ would give NaN.
std::pair<double, double> SurfaceRays::Scene::crossing(const Ray& ray) const {
  double in = 0, out = HUGE_VAL;
  for (int axis = 0; axis < 3; ++axis) {
    const double o = ray.origin[axis], d = ray.dir[axis];
    if (d == 0) {
      if (o < lo[axis] || o > hi[axis]) return {HUGE_VAL, 0};
      continue;
    }
    const double a = (lo[axis] - o) / d, b = (hi[axis] - o) / d;
    in = std::max(in, std::min(a, b)), out = std::min(out, std::max(a, b));
  }
  return {in, out};
}

/// Embree's ray starts where the double ray enters the scene's box, so that its round-off (a
/// share of its origin's coordinates) stays within the slack however far off the origin is.
std::optional<RayHit> SurfaceRays::Scene::firstHit(const Ray& ray) const {
  const auto [in, out] = crossing(ray);
  if (targets.empty() || !(in <= out)) return std::nullopt;
  Context context;
  rtcInitIntersectContext(&context);
  context.scene = this, context.ray = ray, context.start = in;
  const glm::dvec3 origin = ray.origin + in * ray.dir;
  RTCRayHit rayHit{};
  rayHit.ray.org_x = float(origin.x), rayHit.ray.org_y = float(origin.y), rayHit.ray.org_z = float(origin.z);
  rayHit.ray.dir_x = float(ray.dir.x), rayHit.ray.dir_y = float(ray.dir.y), rayHit.ray.dir_z = float(ray.dir.z);
  rayHit.ray.tnear = std::max(0.0f, floatBelow(ray.after - in));
  rayHit.ray.tfar = HUGE_VALF;
  rayHit.ray.mask = ~0u;
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context, &rayHit);
  return context.best;
}

/// Whether the ray meets polygon i beyond `after` and before `best`; then t is where.
bool SurfaceRays::Scene::meets(int i, const Ray& ray, const std::optional<RayHit>& best, double& t) const {
  const Target& target = targets[size_t(i)];
  const double across = glm::dot(target.frame.normal, ray.dir);
  if (across == 0 || (ray.throughBacks && !target.twoSided && across > 0)) return false;
  const double s = glm::dot(target.frame.normal, target.frame.origin - ray.origin) / across;
  if (!(s > ray.after && before(s, i, best))) return false;
  const glm::dvec3 p = ray.origin + s * ray.dir;
  if (glm::any(glm::lessThan(p, target.lo)) || glm::any(glm::greaterThan(p, target.hi))) return false;
  if (!insidePolygon(target.frame, polygons[size_t(i)], p)) return false;
  t = s;
  return true;
}

/// The hit on polygon i at t: its front when the ray comes against its normal.
RayHit SurfaceRays::Scene::hit(int i, const Ray& ray, double t) const {
  const Target& target = targets[size_t(i)];
  return {t, i, target.twoSided || glm::dot(target.frame.normal, ray.dir) < 0};
}

SurfaceRays::SurfaceRays(const std::vector<Polygon>& polygons, const std::vector<bool>& twoSided)
    : scene_(std::make_unique<Scene>(polygons, twoSided)) {}

SurfaceRays::~SurfaceRays() = default;

std::optional<RayHit> SurfaceRays::firstHit(const glm::dvec3& origin, const glm::dvec3& dir,
                                            bool throughBacks, double after) const {
  return scene_->firstHit({origin, dir, throughBacks, after});
}

}  // namespace rad
