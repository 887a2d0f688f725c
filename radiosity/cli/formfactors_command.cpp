// radiosity formfactors SCENE (--from SURFACE | --point X,Y,Z --normal X,Y,Z): the hemicube
// factor from one point to every surface, beside the exact factor where nothing occludes.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "mesh/error.h"
#include "mesh/patch_mesh.h"
#include "radiosity/settings.h"
#include "radiosity/cli/commands.h"
#include "radiosity/hemicube.h"
#include "radiosity/point_polygon.h"

namespace rad::cli {
namespace {

/// Factors that agree to this are the same pixels: the surface is unoccluded.
constexpr double kSamePixels = 1e-12;

struct FormFactorOptions {
  std::string scene, from;
  std::vector<double> point, normal;
  SolverBlock flags;
};

/// The point of a surface to look from: the centroid of its element nearest to its area
/// centroid (so it lies on the surface even when the surface is not convex).
int centralElement(const PatchMesh& mesh, int surface) {
  glm::dvec3 c(0.0);
  double area = 0;
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (mesh.surface(e) == surface && mesh.side(e) == 0) {
      c += mesh.area(e) * mesh.centroid(e);
      area += mesh.area(e);
    }
  c /= area;
  int best = -1;
  double bestDist = HUGE_VAL;
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (mesh.surface(e) == surface && mesh.side(e) == 0) {
      double d = glm::length(mesh.centroid(e) - c);
      if (d < bestDist) bestDist = d, best = e;
    }
  return best;
}

glm::dvec3 vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

void runFormFactors(const FormFactorOptions& o) {
  Scene scene = loadScene(o.scene);
  Settings settings = resolveSettings(scene, o.flags);
  PatchMesh mesh = buildPatchMesh(scene, settings.mesh());
  printWarnings(scene.warnings);
  printWarnings(mesh.warnings);

  glm::dvec3 x, n;
  std::vector<int> excluded;
  uint64_t shooter = 0;
  int fromSurface = -1;
  if (!o.from.empty()) {
    std::string names;
    for (size_t s = 0; s < scene.surfaces.size(); ++s) {
      if (scene.surfaces[s].name == o.from) fromSurface = int(s);
      names += (s ? ", " : "") + scene.surfaces[s].name;
    }
    if (fromSurface < 0)
      throw inputError("--from", "the name of a surface of " + scene.path + " (" + names + ")",
                       "\"" + o.from + "\"");
    int e = centralElement(mesh, fromSurface);
    x = mesh.centroid(e);
    n = mesh.normal(e);
    shooter = uint64_t(e);
    for (int k = 0; k < mesh.elementCount(); ++k)
      if (mesh.surface(k) == fromSurface) excluded.push_back(k);
  } else {
    x = vec3(o.point);
    n = vec3(o.normal);
    for (double c : o.point)
      if (!std::isfinite(c)) throw inputError("--point", "finite coordinates", "NaN or infinity");
    if (!(glm::length(n) > 0) || !std::isfinite(glm::length(n)))
      throw inputError("--normal", "a non-zero finite vector", "a zero or non-finite one");
    n = glm::normalize(n);
  }

  // The full scene, then each surface alone: equal factors mean nothing occludes it.
  HemicubeGeometry all = HemicubeGeometry::fromMesh(mesh);
  double rotation = hemicubeRotation(settings.seed, shooter, 0);
  Hemicube hemicube(all, settings.hemicubeResolution, scene.diagonal());
  FormFactors ff;
  hemicube.compute(x, n, rotation, ff, excluded);
  std::vector<double> perSurface(scene.surfaces.size(), 0.0);
  for (size_t k = 0; k < ff.elements.size(); ++k) perSurface[mesh.surface(ff.elements[k])] += ff.factors[k];

  nlohmann::ordered_json out;
  out["scene"] = scene.path;
  out["point"] = {x.x, x.y, x.z};
  out["normal"] = {n.x, n.y, n.z};
  if (fromSurface >= 0) out["from"] = scene.surfaces[fromSurface].name;
  out["hemicube_resolution"] = settings.hemicubeResolution;
  out["seed"] = settings.seed;
  out["elements"] = mesh.elementCount();
  out["sky"] = ff.sky;
  out["back_faces"] = ff.backFaces;
  out["sum"] = ff.sum();
  out["surfaces"] = nlohmann::json::array();
  for (size_t s = 0; s < scene.surfaces.size(); ++s) {
    if (int(s) == fromSurface) continue;
    HemicubeGeometry alone;
    double exact = 0;
    for (int e = 0; e < mesh.elementCount(); ++e) {
      if (mesh.surface(e) != int(s)) continue;
      auto c = mesh.corners(e);
      alone.addTriangle(c[0], c[1], c[2]);
      if (glm::dot(mesh.normal(e), x - c[0]) > 0)  // only the lit side receives
        exact += pointPolygonFormFactor(x, n, {c[0], c[1], c[2]});
    }
    Hemicube single(alone, settings.hemicubeResolution, scene.diagonal());
    FormFactors ffAlone;
    single.compute(x, n, rotation, ffAlone);
    double fAlone = 0;
    for (double f : ffAlone.factors) fAlone += f;
    nlohmann::ordered_json row;
    row["index"] = s;
    row["name"] = scene.surfaces[s].name;
    row["hemicube"] = perSurface[s];
    bool unoccluded = std::abs(fAlone - perSurface[s]) <= kSamePixels;
    row["occluded"] = !unoccluded;
    if (unoccluded) {
      row["exact"] = exact;
      row["relative_difference"] = exact > 0 ? (perSurface[s] - exact) / exact : 0.0;
    }
    out["surfaces"].push_back(row);
  }
  std::cout << out.dump(2) << "\n";
  if (!std::cout) throw std::runtime_error("standard output: write error");
}

}  // namespace

Command addFormFactorsCommand(CLI::App& app) {
  auto o = std::make_shared<FormFactorOptions>();
  CLI::App* sub = app.add_subcommand(
      "formfactors", "Print, as JSON, the hemicube form factor from a point to every surface and, "
                     "where nothing occludes the surface, the exact factor and the relative difference");
  sub->add_option("scene", o->scene, "Scene file (JSON, version 1)")->required();
  auto from = sub->add_option("--from", o->from, "Look from the middle of this surface (by name)");
  auto point = sub->add_option("--point", o->point, "Look from this point X,Y,Z")
                   ->delimiter(',')->expected(3);
  auto normal = sub->add_option("--normal", o->normal, "Normal X,Y,Z at --point")
                    ->delimiter(',')->expected(3);
  from->excludes(point)->excludes(normal);
  point->needs(normal);
  normal->needs(point);
  addSolverFlags(*sub, o->flags);
  addMeshFlags(*sub, o->flags);
  sub->callback([sub, from, point] {
    if (from->count() == 0 && point->count() == 0)
      throw CLI::RequiredError("--from or --point");
    (void)sub;
  });
  return {sub, [o] { runFormFactors(*o); }};
}

}  // namespace rad::cli
