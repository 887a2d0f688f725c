#pragma once
// Progressive refinement radiosity (Cohen, Chen, Wallace & Greenberg 1988): patches shoot
// their unshot power, elements receive, with an energy ledger kept after every shot.
#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/color.h"
#include "radiosity/settings.h"
#include "radiosity/hemicube.h"

namespace rad {

class PatchMesh;

/// A point a patch shoots from, carrying weights[k] of elements[k]'s unshot power.
struct ShooterSample {
  std::vector<int> elements;
  std::vector<double> weights;
  glm::dvec3 point{0.0}, normal{0.0};
};

/// Where the form factors of a shot come from: hemicubes in the solver, exact injected
/// factors in tests. Calls with different `worker` numbers may run concurrently.
class FactorSource {
 public:
  virtual ~FactorSource() = default;
  /// Factors from sample `index` of patch `patch` to every element (sparse), and what escaped.
  virtual void factors(int patch, int index, const ShooterSample& sample, FormFactors& out,
                       int worker = 0) = 0;
  /// How many workers may call factors() at once.
  virtual int workers() const { return 1; }
};

/// Hemicubes over the whole mesh, turned by (seed, patch, sample), the patch's own elements
/// excluded. Emitting patches may use a finer resolution: direct light carries the sharpest
/// detail (shadows, the floor at a block's base), and emitters shoot from few points.
class HemicubeFactors : public FactorSource {
 public:
  /// workers: hemicubes that may render at once (0: one per hardware thread).
  /// emitterResolution: for emitting patches (0: `resolution`).
  HemicubeFactors(const PatchMesh& mesh, int resolution, double sceneSize, unsigned seed,
                  int workers = 0, int emitterResolution = 0);
  void factors(int patch, int index, const ShooterSample& sample, FormFactors& out,
               int worker = 0) override;
  int workers() const override { return int(hemicubes_.size()); }

 private:
  const PatchMesh& mesh_;
  HemicubeGeometry geometry_;
  std::vector<std::unique_ptr<Hemicube>> hemicubes_;         // one per worker
  std::vector<std::unique_ptr<Hemicube>> emitterHemicubes_;  // one per worker, if finer
  std::vector<bool> emits_;                                   // per patch
  unsigned seed_;
};

/// Power per channel, Σ area·radiosity, in double precision.
struct EnergyLedger {
  glm::dvec3 emitted{0.0}, absorbed{0.0}, escaped{0.0}, unshot{0.0};
  /// |emitted − absorbed − escaped − unshot| / emitted, largest channel (0 without emission).
  double residual() const;
};

/// The defaults are the command line's (mesh/settings.h), except ω: plain shooting here.
struct SolverOptions {
  double tolerance = 1e-3;   ///< stop when unshot/emitted power (luminance) falls below
  long maxShots = 0;         ///< 0: no limit
  double timeLimit = 0;      ///< seconds; 0: no limit
  double overshoot = 1;      ///< ω: shoot ω times the unshot power (1: plain shooting)
  int emitterSamples = kDefaultEmitterSamples;  ///< points on an emitting patch
  int shooterSamples = kDefaultShooterSamples;  ///< at least this many on any other patch
  /// More points on patches near other surfaces (sampleCount).
  double proximitySamples = kDefaultProximitySamples;
  /// Memory for keeping each sample's form factors after its first shot, so that a patch
  /// shooting again costs no hemicube (the factors are the same: same point, same rotation).
  /// A fixed budget, whatever the scene size; 0 recomputes every time.
  size_t factorCacheBytes = size_t(kDefaultFactorCacheMb * 1024 * 1024);
};

/// How many points a patch shoots from: options.emitterSamples on an emitter; otherwise
/// options.shooterSamples, raised to proximitySamples·(D/d)² (at most emitterSamples), D the
/// patch's diameter and d the distance from its centroid to the nearest element of another
/// plane facing it: the proximity error of point shooters falls as the square of the points'
/// spacing (oracles.md §3). Element centroids sit in a grid, so only nearby ones are visited.
class SampleCounter {
 public:
  SampleCounter(const PatchMesh& mesh, const SolverOptions& options);
  int operator()(int patch) const;

 private:
  std::array<int64_t, 3> cellOf(const glm::dvec3& p) const;
  static uint64_t key(const std::array<int64_t, 3>& cell);

  const PatchMesh& mesh_;
  SolverOptions options_;
  double cell_ = 1;
  std::unordered_map<uint64_t, std::vector<int>> grid_;
};

class ProgressiveSolver {
 public:
  enum class Stop { None, Tolerance, MaxShots, TimeLimit };

  ProgressiveSolver(const PatchMesh& mesh, FactorSource& factors, const SolverOptions& options);

  /// Shoots from the patch with the largest unshot power; false once a stop condition holds.
  bool step();
  /// Steps until a stop condition holds.
  void run();

  Stop stopReason() const { return stop_; }
  long shots() const { return shots_; }
  /// Seconds spent in the constructor and in step(), the solver's own time: what the caller
  /// does between steps (measuring, printing) is not counted, nor by the time limit.
  double seconds() const;
  /// Σ|Aᵢ·ΔBᵢ| / Σ Aᵢ·Eᵢ, luminance weighted.
  double unshotFraction() const;
  const EnergyLedger& ledger() const { return ledger_; }
  /// Total power shot so far (luminance), the scale of the ledger's round-off.
  double powerShot() const { return powerShot_; }

  /// Element radiosity B and unshot radiosity ΔB, per channel.
  const std::vector<glm::dvec3>& radiosity() const { return B_; }
  const std::vector<glm::dvec3>& unshot() const { return dB_; }
  /// The part of B that came straight from the emitters' emission (first bounce), per
  /// element: the display replaces it with direct light computed at the vertices by rays.
  const std::vector<glm::dvec3>& direct() const { return direct_; }
  /// The ambient term of Cohen et al. 1988: (Σ Aᵢ ΔBᵢ / Σ Aᵢ) / (1 − ρ̄), ρ̄ the area-weighted
  /// mean reflectance; element i is displayed as Bᵢ + ρᵢ·ambient. withoutEmission: leave out
  /// the emission not yet shot (when the display takes direct light from rays, which already
  /// show its first bounce).
  glm::dvec3 ambient(bool withoutEmission = false) const;
  /// Patches that never shot so far (nothing, or too little, to send).
  int patchesNeverShot() const;
  /// Whether one channel is solved and copied to the others (a grey scene).
  bool grey() const { return grey_; }
  /// Hemicubes (factor computations) so far; shots reuse cached factors.
  long hemicubes() const { return hemicubes_; }
  /// Memory the cached factors take.
  size_t cachedBytes() const { return cachedBytes_; }

 private:
  int pickShooter() const;
  bool stepOnce();
  void shoot(int patch);
  /// Makes sure rows_[patch][i] holds sample i's factors for every sample with power.
  void computeFactors(int patch, const std::vector<glm::dvec3>& powers);
  void setPatchUnshot(int patch, const glm::dvec3& power);
  /// Delivers `power` through one sample's factors to the elements it sees and returns the
  /// power that arrived. T: double in a grey scene (channel r stands for all), else dvec3.
  template <class T>
  glm::dvec3 deliver(const glm::dvec3& power, const FormFactors& row);
  /// Adds the emission part of a shot to direct_.
  void deliverDirect(const glm::dvec3& power, const FormFactors& row);

  const PatchMesh& mesh_;
  FactorSource& factors_;
  SolverOptions options_;
  SampleCounter counter_;
  std::vector<std::vector<ShooterSample>> samples_;
  std::vector<glm::dvec3> B_, dB_, rho_;
  std::vector<glm::dvec3> direct_, dE_;  // received from emission; emission not yet shot
  std::vector<double> area_;
  std::vector<int> patchOf_;
  std::vector<glm::dvec3> patchUnshot_;  // Σ A ΔB over the patch's elements
  std::vector<int> shotsOf_;             // per patch
  double unshotLuminance_ = 0, emittedLuminance_ = 0, powerShot_ = 0;
  glm::dvec3 rhoMean_{0.0};
  double totalArea_ = 0;
  EnergyLedger ledger_;
  long shots_ = 0;
  Stop stop_ = Stop::None;
  std::chrono::steady_clock::time_point start_;
  double elapsed_ = 0;  // seconds spent constructing and in step(): not the caller's time between
  /// Per patch, per sample: its form factors, once computed (kept within the cache budget).
  struct SampleRow {
    FormFactors factors;
    bool ready = false;
  };
  std::vector<std::vector<SampleRow>> rows_;
  size_t cachedBytes_ = 0;
  bool grey_ = false;
  long hemicubes_ = 0;
};


/// True when every element's reflectance and emission are the same in all three channels:
/// one channel then carries the whole solution.
bool isGrey(const PatchMesh& mesh);

/// `count` stratified samples over a patch. Each element is cut into m×m congruent triangles,
/// m chosen so that the patch has at least `count` parts spread by area; the parts are split into `count` strata of
/// about equal area by recursive bisection, and each stratum shoots its parts' shares of
/// their elements' power from its centroid. Each element's weights sum to 1.
std::vector<ShooterSample> patchSamples(const PatchMesh& mesh, int patch, int count);

}  // namespace rad
