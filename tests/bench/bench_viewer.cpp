// A 1024×1024 render of the Cornell box meshed to about 100 000 triangles, through OSMesa and
// through the software backend (the raster core). The radiosities come from one shot: only the
// drawing is timed.
//   build/bin/bench_viewer
#include <benchmark/benchmark.h>

#include <memory>

#include "display/viewer/viewer.h"
#include "mesh/patch_mesh.h"
#include "mesh/results/result_file.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/result.h"
#include "radiosity/shooting/progressive_solver.h"

namespace {

/// The result mesh, made once: Cornell box at element edge 10 mm, one shot of the light.
const rad::ResultFile& result() {
  static std::unique_ptr<rad::ResultFile> cached;
  if (!cached) {
    rad::Scene scene = rad::loadScene(std::string(RAD_SOURCE_DIR) + "/scenes/cornell.json");
    rad::PatchMesh mesh = rad::buildPatchMesh(scene, {10.0, 30.0});
    rad::HemicubeFactors factors(mesh, 128, scene.diagonal(), 1);
    rad::SolverOptions options;
    options.maxShots = 1;
    rad::ProgressiveSolver solver(mesh, factors, options);
    solver.run();
    const std::string path = "/tmp/bench_viewer_cornell.ply";
    rad::writeResult(path, mesh, solver.radiosity(), glm::dvec3(0.0),
                     rad::autoExposure(mesh, solver.radiosity()), *scene.camera);
    cached = std::make_unique<rad::ResultFile>(rad::readResultFile(path));
  }
  return *cached;
}

void BM_Render1024(benchmark::State& state) {
  const auto& mesh = result();
  rad::viewer::RenderOptions o;
  o.width = o.height = 1024;
  o.backend = state.range(0) ? rad::viewer::Backend::Software : rad::viewer::Backend::OsMesa;
  state.SetLabel(state.range(0) ? "software" : "osmesa");
  for (auto _ : state) benchmark::DoNotOptimize(rad::viewer::render(mesh, o));
  state.counters["triangles"] = double(mesh.faces.size());
}
BENCHMARK(BM_Render1024)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
