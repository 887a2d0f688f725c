// radiosity info SCENE: surfaces, areas, materials, emitters, patch and element counts.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <tuple>

#include "mesh/base/number_text.h"
#include "mesh/base/parallel.h"
#include "mesh/patch_mesh.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/cli/commands.h"
#include "radiosity/settings.h"

namespace rad::cli {
namespace {

struct InfoOptions {
  std::string scene;
  SolverBlock flags;
};

/// A colour as three numbers of four significant digits.
std::string rgb(const glm::dvec3& c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.4g %.4g %.4g", c.x, c.y, c.z);
  return buf;
}

/// One row of the materials table.
void printMaterialRow(const Material& m) {
  std::printf("  %-16s reflectance %-22s emission %-22s%s%s\n", m.name.c_str(), rgb(m.reflectance).c_str(),
              rgb(m.emission).c_str(), m.preset.empty() ? "" : " preset ", m.preset.c_str());
}

/// The materials table.
void printMaterials(const Scene& scene) {
  std::printf("\nmaterials\n");
  for (const auto& m : scene.materials) printMaterialRow(m);
}

/// The scene's file, size and meshing settings, then its materials.
void printScene(const Scene& scene, const Settings& settings) {
  std::printf("scene       %s%s%s\n", scene.path.c_str(), scene.units.empty() ? "" : ", units ",
              scene.units.c_str());
  std::printf("size        diagonal %.6g\n", scene.diagonal());
  std::printf("meshing     max element edge %.6g, max patch edge %.6g\n", settings.maxElementEdge,
              settings.maxPatchEdge);
  printMaterials(scene);
}

/// The totals of the surface table: counts, then areas.
void printTotals(const Scene& scene, const PatchMesh& mesh, double total, double emitting) {
  std::printf("\ntotals      %zu surfaces, %zu patches, %d elements, %zu vertices\n",
              scene.surfaces.size(), mesh.patches.size(), mesh.elementCount(),
              mesh.mesh.n_vertices());
  std::printf("area        %.9g (all sides), emitting %.9g\n", total, emitting);
}

/// One row of the surface table.
void printSurfaceRow(const Scene& scene, const PatchMesh& mesh, size_t s) {
  const Surface& surface = scene.surfaces[s];
  const Material& material = scene.materials[surface.material];
  const SurfaceSummary& summary = mesh.surfaces[s];
  std::printf("  %3zu %-20s %-12s %14.6g %6d %8d %9d%s\n", s, surface.name.c_str(),
              material.name.c_str(), summary.area, surface.twoSided ? 2 : 1, summary.patches,
              summary.elements, material.emits() ? "  emitter" : "");
}

/// The area of every surface side in all, and of the emitting surfaces.
std::pair<double, double> surfaceAreas(const Scene& scene, const PatchMesh& mesh) {
  double total = 0, emitting = 0;
  for (size_t s = 0; s < scene.surfaces.size(); ++s) {
    const Surface& surface = scene.surfaces[s];
    total += mesh.surfaces[s].area * (surface.twoSided ? 2 : 1);
    if (scene.materials[surface.material].emits()) emitting += mesh.surfaces[s].area;
  }
  return {total, emitting};
}

/// The surface table, then the totals.
void printSurfaces(const Scene& scene, const PatchMesh& mesh) {
  std::printf("\nsurfaces\n  %3s %-20s %-12s %14s %6s %8s %9s\n", "#", "name", "material", "area",
              "sides", "patches", "elements");
  for (size_t s = 0; s < scene.surfaces.size(); ++s) printSurfaceRow(scene, mesh, s);
  const auto [total, emitting] = surfaceAreas(scene, mesh);
  printTotals(scene, mesh, total, emitting);
}

/// The area cut away in all.
double cutAwayArea(const PatchMesh& mesh) {
  double cut = 0;
  for (const auto& c : mesh.cutAway) cut += c.area;
  return cut;
}

/// The names of the surfaces that enclose a cut-away part, comma-separated.
std::string enclosingNames(const Scene& scene, const std::vector<int>& enclosedBy) {
  std::string by;
  for (int s : enclosedBy) by += (by.empty() ? "" : ", ") + scene.surfaces[s].name;
  return by;
}

/// Contacts: where surfaces touch, the mesh is cut; what they enclose is left out.
void printContacts(const Scene& scene, const PatchMesh& mesh) {
  int seam = 0;
  for (auto v : mesh.mesh.vertices()) seam += mesh.seam(v);
  std::printf("contacts    %d lines where surfaces touch; %.9g cut away; %d vertices on seams (a vertex per side)\n",
              mesh.contactLines, cutAwayArea(mesh), seam);
  for (const auto& c : mesh.cutAway) {
    const std::string by = enclosingNames(scene, c.enclosedBy);
    std::printf("  %-20s %14.9g cut away: enclosed by %s\n", scene.surfaces[c.surface].name.c_str(),
                c.area, by.c_str());
  }
}

/// How the direct light is shown: at the vertices by rays (points, rays) or from the hemicubes.
std::string directLine(const DirectLight* direct) {
  return direct ? "at vertices by rays, " + std::to_string(direct->samples()) + " points on " +
                      std::to_string(direct->lights().size()) + " lights, " + std::to_string(direct->rays()) +
                      " rays (" + std::to_string(direct->seenWhole()) + " lights seen whole without one)"
                : "from the hemicubes";
}

/// What adaptive refinement did.
void printAdaptive(const Settings& settings, const AdaptiveStats& adaptive) {
  std::printf("adaptive    %d -> %d elements in %d rounds (min element edge %.6g, contrast %.3g), "
              "%.3f s\n", adaptive.elementsBefore, adaptive.elementsAfter, adaptive.rounds,
              settings.minElementEdge, settings.contrast, adaptive.seconds);
}

/// What the final gather will do.
std::string gatherLine(const MeshedScene& meshed) {
  if (!meshed.gather.on) return meshed.settings.finalGather ? "skipped (over its budget)" : "off";
  const PatchMesh& drawn = meshed.base ? *meshed.base : meshed.mesh;
  const long own = ownHemicubes(meshed);
  const long added = long(meshed.mesh.mesh.n_vertices()) - long(drawn.mesh.n_vertices());
  const std::string others =
      meshed.base ? " before refinement and at " + std::to_string(own) + " it added beside another surface (its other " +
                        std::to_string(added - own) + " interpolate)"
                  : "";
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.2g", meshed.gather.estimate.seconds(workerCount(0)));
  return "at " + std::to_string(drawn.mesh.n_vertices()) + " vertices" + others + " over " +
         std::to_string(drawn.elementCount()) + " elements, hemicubes " + std::to_string(meshed.settings.gatherResolution) +
         ", drawing " + shortNumberText(std::round(meshed.gather.estimate.drawn)) + " triangles and resolving " +
         shortNumberText(std::round(meshed.gather.estimate.located)) + " pixels to elements in all (about " +
         seconds + " s), keeping " +
         shortNumberText(std::round(meshed.gather.estimate.factors)) + " factors" +
         (meshed.gather.estimate.iterates(GatherOptions{}) ? "" : " (over its memory: gathered once)");
}

/// Emitters, mesh quality, refinement, the direct light and the time taken.
void printMeshing(const MeshedScene& meshed, double seconds) {
  const auto& [scene, settings, mesh, direct, adaptive] = std::tie(meshed.scene, meshed.settings, meshed.mesh,
                                                                 meshed.direct, meshed.adaptive);
  std::printf("emitters    %s\n", scene.hasEmitter() ? "yes" : "none (solve needs at least one)");
  for (const std::string& note : scene.notes) std::printf("note        %s\n", note.c_str());
  std::printf("quality     min angle %.2f deg, max element edge %.6g, widest patch %.6g\n",
              mesh.stats.minAngleDeg, mesh.stats.maxEdge, mesh.stats.maxPatchDiameter);
  if (settings.adaptive) printAdaptive(settings, adaptive);
  std::printf("direct      %s\n", directLine(direct.get()).c_str());
  std::printf("gather      %s\n", gatherLine(meshed).c_str());
  std::printf("time        %.3f s to mesh (%d boundary agreement rounds)\n", seconds, mesh.stats.rounds);
}

/// The seconds of every stage but loading the scene.
double secondsToMesh(const StageTimes& stages) {
  double seconds = 0;
  for (const StageTime& s : stages.list()) seconds += s.name == "loading" ? 0 : s.seconds;
  return seconds;
}

/// The time of each stage, then their total.
void printStages(const StageTimes& stages) {
  std::printf("\nstages                         seconds  peak MiB\n");
  for (const StageTime& s : stages.list()) std::printf("  %-28s %9.3f %9.0f\n", s.name.c_str(), s.seconds, s.peakMiB);
  std::printf("  %-28s %9.3f %9.0f\n", "total", stages.total(), StageTimes::peakMiB());
}

/// Flushes standard output; a failed write is an error.
void flushOutput() {
  std::fflush(stdout);
  if (std::ferror(stdout)) throw std::runtime_error("standard output: write error");
}

void runInfo(const InfoOptions& o) {
  StageTimes stages;
  const MeshedScene meshed = loadAndMesh(o.scene, loadScene, o.flags, false, stages);
  printScene(meshed.scene, meshed.settings);
  printSurfaces(meshed.scene, meshed.mesh);
  printContacts(meshed.scene, meshed.mesh);
  printMeshing(meshed, secondsToMesh(stages));
  printStages(stages);
  flushOutput();
}

}  // namespace

Command addInfoCommand(CLI::App& app) {
  Subcommand<InfoOptions> c(app, "info",
                            "Print the scene's surfaces, materials, emitters, "
                            "areas and patch and element counts");
  addScene(*c.app, c.o->scene);
  addMeshFlags(*c.app, c.o->flags);
  return c.runs(runInfo);
}

}  // namespace rad::cli
