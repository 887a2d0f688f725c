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

/// Embree's copy of a ray from `origin` along `dir`, from `after` along it (0 at the earliest).
RTCRayHit floatRay(const glm::dvec3& origin, const glm::dvec3& dir, double after) {
  RTCRayHit r{};
  r.ray.org_x = float(origin.x), r.ray.org_y = float(origin.y), r.ray.org_z = float(origin.z);
  r.ray.dir_x = float(dir.x), r.ray.dir_y = float(dir.y), r.ray.dir_z = float(dir.z);
  r.ray.tnear = std::max(0.0f, floatBelow(after));
  r.ray.tfar = HUGE_VALF;
  r.ray.mask = ~0u;
  r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  return r;
}

/// An Embree device and scene, released with it (also when building the scene throws).
struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  EmbreeScene() = default;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  ~EmbreeScene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

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

  /// The targets, the box round them and the slack, then Embree's scene.
  Scene(const std::vector<Polygon>& polygons, const std::vector<bool>& twoSided);

  /// A polygon's plane and box.
  static Target target(const Polygon& polygon, bool twoSided);
  /// One user primitive per polygon: Embree asks for its box and leaves meeting it to
  /// `intersect`.
  void build();
  /// Embree's box of a polygon: its box widened by the slack, rounded outward to float.
  static void bounds(const RTCBoundsFunctionArguments* args);
  /// Meets the polygon whose box Embree's ray entered, with the double ray of the context.
  static void intersect(const RTCIntersectFunctionNArguments* args);
  /// The distances along the ray at which it enters the box round the targets (0 at the
  /// earliest) and leaves it: in after out when it misses.
  std::pair<double, double> crossing(const Ray& ray) const;
  std::optional<RayHit> firstHit(const Ray& ray) const;
  /// Whether the ray meets polygon i beyond `after` and before `best`; then t is where.
  bool meets(int i, const Ray& ray, const std::optional<RayHit>& best, double& t) const;
  /// The hit on polygon i at t: its front when the ray comes against its normal.
  RayHit hit(int i, const Ray& ray, double t) const;

  const std::vector<Polygon>& polygons;
  std::vector<Target> targets;
  glm::dvec3 lo{HUGE_VAL}, hi{-HUGE_VAL};  ///< round every target, widened by `slack`
  double slack = 0;                        ///< how far Embree's boxes reach beyond the targets'
  EmbreeScene embree;
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

void SurfaceRays::Scene::build() {
  embree.device = rtcNewDevice(nullptr);
  embree.scene = rtcNewScene(embree.device);
  rtcSetSceneFlags(embree.scene, RTC_SCENE_FLAG_ROBUST);  // box tests rounded outward
  RTCGeometry geometry = rtcNewGeometry(embree.device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, unsigned(targets.size()));
  rtcSetGeometryUserData(geometry, this);
  rtcSetGeometryBoundsFunction(geometry, bounds, this);
  rtcSetGeometryIntersectFunction(geometry, intersect);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(embree.scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(embree.scene);
  if (rtcGetDeviceError(embree.device) != RTC_ERROR_NONE) throw std::runtime_error("embree: scene build failed");
}

void SurfaceRays::Scene::bounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = *static_cast<const Scene*>(args->geometryUserPtr);
  const Target& target = s.targets[args->primID];
  const glm::dvec3 lo = target.lo - s.slack, hi = target.hi + s.slack;
  RTCBounds& b = *args->bounds_o;
  b.lower_x = floatBelow(lo.x), b.lower_y = floatBelow(lo.y), b.lower_z = floatBelow(lo.z);
  b.upper_x = floatAbove(hi.x), b.upper_y = floatAbove(hi.y), b.upper_z = floatAbove(hi.z);
}

void SurfaceRays::Scene::intersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto& context = *static_cast<Context*>(args->context);
  const int i = int(args->primID);
  double t = 0;
  if (!context.scene->meets(i, context.ray, context.best, t)) return;
  context.best = context.scene->hit(i, context.ray, t);
  // Embree skips the boxes beyond the hit from now on; rounded up, it keeps those as near, where
  // a tie may still win.
  RTCRayN_tfar(RTCRayHitN_RayN(args->rayhit, args->N), args->N, 0) = floatAbove(t - context.start);
}

std::pair<double, double> SurfaceRays::Scene::crossing(const Ray& ray) const {
  double in = 0, out = HUGE_VAL;
  for (int axis = 0; axis < 3; ++axis) {
    const double o = ray.origin[axis], d = ray.dir[axis];
    if (d == 0) {  // tested apart, where 0 · ∞ would give NaN
      if (o < lo[axis] || o > hi[axis]) return {HUGE_VAL, 0};
      continue;
    }
    const double a = (lo[axis] - o) / d, b = (hi[axis] - o) / d;
    in = std::max(in, std::min(a, b)), out = std::min(out, std::max(a, b));
  }
  return {in, out};
}

std::optional<RayHit> SurfaceRays::Scene::firstHit(const Ray& ray) const {
  const auto [in, out] = crossing(ray);
  if (targets.empty() || !(in <= out)) return std::nullopt;
  Context context;
  rtcInitIntersectContext(&context);
  context.scene = this, context.ray = ray, context.start = in;
  // Embree's ray starts where the double ray enters the box round the targets, so that its
  // origin's round-off stays within the slack however far off the origin is.
  RTCRayHit floatHit = floatRay(ray.origin + in * ray.dir, ray.dir, ray.after - in);
  rtcIntersect1(embree.scene, &context, &floatHit);
  return context.best;
}

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
