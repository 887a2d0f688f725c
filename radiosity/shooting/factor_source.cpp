#include "radiosity/shooting/factor_source.h"

#include "mesh/base/error.h"
#include "mesh/base/parallel.h"
#include "mesh/patch_mesh.h"

namespace rad {

HemicubeFactors::HemicubeFactors(const PatchMesh& mesh, int resolution, double sceneSize,
                                 unsigned seed, int workers, int emitterResolution, bool regions)
    : mesh_(mesh), sceneSize_(sceneSize), resolution_(resolution), seed_(seed) {
  if (regions)
    regions_ = std::make_unique<FlatRegions>(mesh, sceneSize);
  else
    geometry_ = HemicubeGeometry::fromMesh(mesh);
  workers = workerCount(workers);
  otherHemicubes_.resize(size_t(workers));
  for (int w = 0; w < workers; ++w) hemicubes_.push_back(hemicube(resolution));
  if (emitterResolution > 0 && emitterResolution != resolution)
    for (int w = 0; w < workers; ++w) emitterHemicubes_.push_back(hemicube(emitterResolution));
  for (int p = 0; p < int(mesh.patches.size()); ++p) emits_.push_back(mesh.emits(p));
}

std::unique_ptr<Hemicube> HemicubeFactors::hemicube(int resolution) const {
  return regions_ ? std::make_unique<Hemicube>(*regions_, resolution, sceneSize_)
                  : std::make_unique<Hemicube>(geometry_, resolution, sceneSize_);
}

void HemicubeFactors::factors(const Shooter& shooter, int index, const ShooterSample& sample,
                              FormFactors& out, int worker) {
  const bool alone = shooter.cluster < 0;
  RAD_CHECK(alone || shooter.elements);
  const bool finer = alone && emits_[size_t(shooter.patch)] && !emitterHemicubes_.empty();
  Hemicube* hemicube = finer ? emitterHemicubes_[worker].get() : hemicubes_[worker].get();
  if (!finer && shooter.resolution > 0 && shooter.resolution != resolution_) {
    auto& other = otherHemicubes_[size_t(worker)][shooter.resolution];  // this worker's own
    if (!other) other = this->hemicube(shooter.resolution);
    hemicube = other.get();
  }
  // A cluster's rotations follow the patches', so that no cluster turns as a patch does.
  const uint64_t stream = alone ? uint64_t(shooter.patch) : uint64_t(emits_.size()) + uint64_t(shooter.cluster);
  hemicube->compute(sample.point, sample.normal, hemicubeRotation(seed_, stream, uint64_t(index)), out,
                    alone ? mesh_.patches[size_t(shooter.patch)].elements : *shooter.elements);
}

}  // namespace rad
