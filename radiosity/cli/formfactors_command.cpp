// radiosity formfactors SCENE (--from SURFACE | --point X,Y,Z --normal X,Y,Z): the hemicube
// factor from one point to every surface, beside the exact factor where nothing occludes.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <numeric>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "mesh/base/error.h"
#include "mesh/patch_mesh.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/cli/commands.h"
#include "radiosity/formfactors/hemicube.h"
#include "radiosity/formfactors/point_polygon.h"
#include "radiosity/settings.h"

namespace rad::cli {
namespace {

/// Factors that agree to this are the same pixels: the surface is unoccluded.
constexpr double kSamePixels = 1e-12;

struct FormFactorOptions {
  std::string scene, from;
  std::vector<double> point, normal;
  SolverBlock flags;
};

/// The elements of one surface: both sides, or only its front side when `frontOnly`.
std::vector<int> elementsOf(const PatchMesh& mesh, int surface, bool frontOnly) {
  std::vector<int> elements;
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (mesh.surface(e) == surface && (!frontOnly || mesh.side(e) == 0)) elements.push_back(e);
  return elements;
}

/// The area-weighted centroid of these elements.
glm::dvec3 areaCentroid(const PatchMesh& mesh, const std::vector<int>& elements) {
  glm::dvec3 c(0.0);
  double area = 0;
  for (const int e : elements) {
    c += mesh.area(e) * mesh.centroid(e);
    area += mesh.area(e);
  }
  return c /= area;
}

/// The point of a surface to look from: the centroid of its element nearest to its area
/// centroid (so it lies on the surface even when the surface is not convex).
int centralElement(const PatchMesh& mesh, int surface) {
  const std::vector<int> front = elementsOf(mesh, surface, true);
  const glm::dvec3 c = areaCentroid(mesh, front);
  int best = -1;
  double bestDist = HUGE_VAL;
  for (const int e : front)
    if (const double d = glm::length(mesh.centroid(e) - c); d < bestDist) bestDist = d, best = e;
  return best;
}

/// The three values of a --point or --normal option.
glm::dvec3 vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

/// Where the factors are seen from: a point and its unit normal, the elements that receive
/// nothing (the surface looked from), the shooter number that turns the hemicube, and the
/// surface (-1 for a point given by the user).
struct Viewpoint {
  glm::dvec3 x{0.0}, n{0.0};
  std::vector<int> excluded;
  uint64_t shooter = 0;
  int fromSurface = -1;
};

/// The index of the surface named `name` (--from); an error lists the names there are.
int surfaceNamed(const Scene& scene, const std::string& name) {
  int found = -1;
  std::string names;
  for (size_t s = 0; s < scene.surfaces.size(); ++s) {
    if (scene.surfaces[s].name == name) found = int(s);
    names += (s ? ", " : "") + scene.surfaces[s].name;
  }
  if (found < 0)
    throw inputError("--from", "the name of a surface of " + scene.path + " (" + names + ")", "\"" + name + "\"");
  return found;
}

/// The middle of the surface named `name` (--from).
Viewpoint surfaceViewpoint(const Scene& scene, const PatchMesh& mesh, const std::string& name) {
  Viewpoint view;
  view.fromSurface = surfaceNamed(scene, name);
  int e = centralElement(mesh, view.fromSurface);
  view.x = mesh.centroid(e);
  view.n = mesh.normal(e);
  view.shooter = uint64_t(e);
  view.excluded = elementsOf(mesh, view.fromSurface, false);
  return view;
}

/// Refuses a --point that is not finite and a --normal that is zero or not finite.
void checkPointAndNormal(const std::vector<double>& point, const glm::dvec3& normal) {
  for (double c : point)
    if (!std::isfinite(c)) throw inputError("--point", "finite coordinates", "NaN or infinity");
  if (!(glm::length(normal) > 0) || !std::isfinite(glm::length(normal)))
    throw inputError("--normal", "a non-zero finite vector", "a zero or non-finite one");
}

/// The point and normal given by --point and --normal.
Viewpoint pointViewpoint(const FormFactorOptions& o) {
  checkPointAndNormal(o.point, vec3(o.normal));
  Viewpoint view;
  view.x = vec3(o.point), view.n = glm::normalize(vec3(o.normal));
  return view;
}

/// The factor of the surface drawn `alone` on its own hemicube: its pixels when nothing occludes it.
double aloneFactor(const HemicubeGeometry& alone, const Settings& settings, const Scene& scene,
                   const Viewpoint& view, double rotation) {
  Hemicube single(alone, settings.shooting(settings.finalGather).hemicubeResolution, scene.diagonal());
  FormFactors ffAlone;
  single.compute(view.x, view.n, rotation, ffAlone);
  return std::accumulate(ffAlone.factors.begin(), ffAlone.factors.end(), 0.0);
}

/// Whether the surface is occluded (its factor alone differs) and, if not, the exact factor beside.
void addOcclusion(nlohmann::ordered_json& row, double hemicube, double fAlone, double exact) {
  bool unoccluded = std::abs(fAlone - hemicube) <= kSamePixels;
  row["occluded"] = !unoccluded;
  if (unoccluded) {
    row["exact"] = exact;
    row["relative_difference"] = exact > 0 ? (hemicube - exact) / exact : 0.0;
  }
}

/// Surface s's triangles drawn alone, and the exact factor of their lit sides from the view.
struct SurfaceAlone {
  HemicubeGeometry geometry;
  double exact = 0;

  SurfaceAlone(const PatchMesh& mesh, const Viewpoint& view, size_t s) {
    for (int e = 0; e < mesh.elementCount(); ++e) {
      if (mesh.surface(e) != int(s)) continue;
      auto c = mesh.corners(e);
      geometry.addTriangle(c[0], c[1], c[2]);
      if (glm::dot(mesh.normal(e), view.x - c[0]) > 0)  // only the lit side receives
        exact += pointPolygonFormFactor(view.x, view.n, {c[0], c[1], c[2]});
    }
    // A two-sided surface's sides are drawn as the full hemicube draws them: the one facing the view.
    geometry.markTwoSided(mesh, std::vector<int>(geometry.elementCount(), int(s)));
  }
};

/// Surface s's row: its hemicube factor (`hemicube`, in the full scene) and, when drawing it
/// alone gives the same factor (nothing occludes it), the exact factor beside it.
nlohmann::ordered_json surfaceRow(const Scene& scene, const PatchMesh& mesh, const Settings& settings,
                                  const Viewpoint& view, double rotation, size_t s, double hemicube) {
  const SurfaceAlone alone(mesh, view, s);
  const double fAlone = aloneFactor(alone.geometry, settings, scene, view, rotation);
  nlohmann::ordered_json row;
  row["index"] = s;
  row["name"] = scene.surfaces[s].name;
  row["hemicube"] = hemicube;
  addOcclusion(row, hemicube, fAlone, alone.exact);
  return row;
}

/// The hemicube's settings and the full hemicube's totals.
void addTotals(nlohmann::ordered_json& out, const PatchMesh& mesh, const Settings& settings, const FormFactors& ff) {
  out["hemicube_resolution"] = settings.shooting(settings.finalGather).hemicubeResolution;
  out["seed"] = settings.seed;
  out["elements"] = mesh.elementCount();
  out["sky"] = ff.sky;
  out["back_faces"] = ff.backFaces;
  out["sum"] = ff.sum();
}

/// What the factors are of (scene, point, settings) and the full hemicube's totals; the
/// surfaces' rows to come.
nlohmann::ordered_json summary(const Scene& scene, const PatchMesh& mesh, const Settings& settings,
                               const Viewpoint& view, const FormFactors& ff) {
  nlohmann::ordered_json out;
  out["scene"] = scene.path;
  out["point"] = {view.x.x, view.x.y, view.x.z};
  out["normal"] = {view.n.x, view.n.y, view.n.z};
  if (view.fromSurface >= 0) out["from"] = scene.surfaces[view.fromSurface].name;
  addTotals(out, mesh, settings, ff);
  out["surfaces"] = nlohmann::json::array();
  return out;
}

/// The full hemicube's factors summed per surface.
std::vector<double> perSurfaceFactors(const FormFactors& ff, const PatchMesh& mesh, size_t surfaces) {
  std::vector<double> perSurface(surfaces, 0.0);
  for (size_t k = 0; k < ff.elements.size(); ++k) perSurface[mesh.surface(ff.elements[k])] += ff.factors[k];
  return perSurface;
}

/// The factors from the view on the full scene's hemicube, turned by `rotation`.
FormFactors fullFactors(const Scene& scene, const PatchMesh& mesh, const Settings& settings, const Viewpoint& view,
                        double rotation) {
  HemicubeGeometry all = HemicubeGeometry::fromMesh(mesh);
  Hemicube hemicube(all, settings.shooting(settings.finalGather).hemicubeResolution, scene.diagonal());
  FormFactors ff;
  hemicube.compute(view.x, view.n, rotation, ff, view.excluded);
  return ff;
}

/// Prints the JSON on standard output; a failed write is an error.
void printJson(const nlohmann::ordered_json& out) {
  std::cout << out.dump(2) << "\n";
  if (!std::cout) throw std::runtime_error("standard output: write error");
}

/// The factors from the view as JSON: the summary, then a row for every other surface.
nlohmann::ordered_json factorsJson(const Scene& scene, const PatchMesh& mesh, const Settings& settings,
                                   const Viewpoint& view) {
  // The full scene, then each surface alone: equal factors mean nothing occludes it.
  double rotation = hemicubeRotation(settings.seed, view.shooter, 0);
  const FormFactors ff = fullFactors(scene, mesh, settings, view, rotation);
  const std::vector<double> perSurface = perSurfaceFactors(ff, mesh, scene.surfaces.size());
  nlohmann::ordered_json out = summary(scene, mesh, settings, view, ff);
  for (size_t s = 0; s < scene.surfaces.size(); ++s)
    if (int(s) != view.fromSurface)
      out["surfaces"].push_back(surfaceRow(scene, mesh, settings, view, rotation, s, perSurface[s]));
  return out;
}

void runFormFactors(const FormFactorOptions& o) {
  Scene scene = loadScene(o.scene);
  Settings settings = resolveSettings(scene, o.flags);
  PatchMesh mesh = buildPatchMesh(scene, settings.mesh());
  printWarnings(scene.warnings);
  printWarnings(mesh.warnings);
  const Viewpoint view = o.from.empty() ? pointViewpoint(o) : surfaceViewpoint(scene, mesh, o.from);
  printJson(factorsJson(scene, mesh, settings, view));
}

/// --from, or --point with --normal: where to look from, one of the two required.
void addViewFlags(CLI::App& sub, FormFactorOptions& o) {
  auto from = sub.add_option("--from", o.from, "Look from the middle of this surface (by name)");
  auto point = sub.add_option("--point", o.point, "Look from this point X,Y,Z")->delimiter(',')->expected(3);
  auto normal = sub.add_option("--normal", o.normal, "Normal X,Y,Z at --point")->delimiter(',')->expected(3);
  from->excludes(point)->excludes(normal);
  point->needs(normal);
  normal->needs(point);
  sub.callback([from, point] {
    if (from->count() == 0 && point->count() == 0) throw CLI::RequiredError("--from or --point");
  });
}

}  // namespace

Command addFormFactorsCommand(CLI::App& app) {
  Subcommand<FormFactorOptions> c(app, "formfactors",
                                  "Print, as JSON, the hemicube form factor from a point to every surface and, "
                                  "where nothing occludes the surface, the exact factor and the relative difference");
  addScene(*c.app, c.o->scene);
  addViewFlags(*c.app, *c.o);
  addSolverFlags(*c.app, c.o->flags);
  addMeshFlags(*c.app, c.o->flags);
  return c.runs(runFormFactors);
}

}  // namespace rad::cli
