#include "radiosity/factor_source.h"

#include "mesh/parallel.h"
#include "mesh/patch_mesh.h"

namespace rad {

HemicubeFactors::HemicubeFactors(const PatchMesh& mesh, int resolution, double sceneSize,
                                 unsigned seed, int workers, int emitterResolution)
    : mesh_(mesh), geometry_(HemicubeGeometry::fromMesh(mesh)), seed_(seed) {
  workers = workerCount(workers);
  for (int w = 0; w < workers; ++w)
    hemicubes_.push_back(std::make_unique<Hemicube>(geometry_, resolution, sceneSize));
  if (emitterResolution > 0 && emitterResolution != resolution)
    for (int w = 0; w < workers; ++w)
      emitterHemicubes_.push_back(std::make_unique<Hemicube>(geometry_, emitterResolution, sceneSize));
  for (int p = 0; p < int(mesh.patches.size()); ++p) emits_.push_back(mesh.emits(p));
}

void HemicubeFactors::factors(int patch, int index, const ShooterSample& sample,
                              FormFactors& out, int worker) {
  auto& hemicube = emits_[size_t(patch)] && !emitterHemicubes_.empty() ? emitterHemicubes_[worker]
                                                                       : hemicubes_[worker];
  hemicube->compute(sample.point, sample.normal,
                    hemicubeRotation(seed_, uint64_t(patch), uint64_t(index)), out,
                    mesh_.patches[patch].elements);
}

}  // namespace rad
