#pragma once
// Where the form factors of a shot come from: hemicubes in the solver, exact injected
// factors in tests.
#include <map>
#include <memory>
#include <vector>

#include "radiosity/formfactors/flat_regions.h"
#include "radiosity/formfactors/hemicube.h"
#include "radiosity/shooting/shooter_samples.h"

namespace rad {

class PatchMesh;

/// What shoots a sample: a patch, or a cluster of coplanar patches (shooter_clusters.h).
struct Shooter {
  int patch = 0;     ///< the patch; for a cluster, its first patch (its surface and plane)
  int cluster = -1;  ///< the cluster, or -1: the patch alone
  /// A cluster's elements, which its hemicubes leave out as a patch's leave out its own.
  const std::vector<int>* elements = nullptr;
  /// Pixels across the top face of this shot's hemicubes (0: the source's own choice).
  int resolution = 0;
};

/// The factors from one shooter sample to every element. Calls with different `worker`
/// numbers may run concurrently.
class FactorSource {
 public:
  virtual ~FactorSource() = default;
  /// Factors from sample `index` of the shooter to every element (sparse), and what escaped.
  virtual void factors(const Shooter& shooter, int index, const ShooterSample& sample,
                       FormFactors& out, int worker = 0) = 0;
  /// How many workers may call factors() at once.
  virtual int workers() const { return 1; }
};

/// Hemicubes over the whole mesh, turned by (seed, shooter, sample), the shooter's own
/// elements excluded. Emitting patches may use a finer resolution: direct light carries the sharpest
/// detail (shadows, the floor at a block's base), and emitters shoot from few points.
class HemicubeFactors : public FactorSource {
 public:
  /// workers: hemicubes that may render at once (0: one per hardware thread).
  /// emitterResolution: for emitting patches (0: `resolution`). regions: draw the mesh's flat
  /// regions and resolve pixels to elements (FlatRegions) instead of drawing every element.
  HemicubeFactors(const PatchMesh& mesh, int resolution, double sceneSize, unsigned seed,
                  int workers = 0, int emitterResolution = 0, bool regions = false);
  void factors(const Shooter& shooter, int index, const ShooterSample& sample, FormFactors& out,
               int worker = 0) override;
  int workers() const override { return int(hemicubes_.size()); }

 private:
  std::unique_ptr<Hemicube> hemicube(int resolution) const;

  const PatchMesh& mesh_;
  double sceneSize_;
  int resolution_;
  HemicubeGeometry geometry_;
  std::unique_ptr<FlatRegions> regions_;                      // if drawn
  std::vector<std::unique_ptr<Hemicube>> hemicubes_;         // one per worker
  std::vector<std::unique_ptr<Hemicube>> emitterHemicubes_;  // one per worker, if finer
  /// Per worker, hemicubes at the other resolutions shots asked for, made when first asked.
  std::vector<std::map<int, std::unique_ptr<Hemicube>>> otherHemicubes_;
  std::vector<bool> emits_;                                   // per patch
  unsigned seed_;
};

}  // namespace rad
