#pragma once
// Progressive refinement radiosity (Cohen, Chen, Wallace & Greenberg 1988): patches shoot
// their unshot power, elements receive, with an energy ledger kept after every shot.
#include <chrono>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/base/color.h"
#include "radiosity/shooting/factor_cache.h"
#include "radiosity/shooting/factor_source.h"
#include "radiosity/shooting/shooter_clusters.h"
#include "radiosity/shooting/shooter_samples.h"
#include "radiosity/shooting/solver_options.h"

namespace rad {

class PatchMesh;

/// Power per channel, Σ area·radiosity, in double precision.
struct EnergyLedger {
  glm::dvec3 emitted{0.0}, absorbed{0.0}, escaped{0.0}, unshot{0.0};
  /// |emitted − absorbed − escaped − unshot| / emitted, largest channel (0 without emission).
  double residual() const;
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
  /// Shots in which a cluster of patches shot together.
  long clusterShots() const { return clusterShots_; }
  /// Shots that drew hemicubes coarser than the finest resolution (options.followingResolution);
  /// a shot whose factors all came from the cache draws none.
  long coarserShots() const { return coarserShots_; }
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
  /// The ambient term of Cohen et al. 1988, (Σ Aᵢ ΔBᵢ / Σ Aᵢ) / (1 − ρ̄) with ρ̄ the
  /// area-weighted mean reflectance, for a scene that loses a share f of what is shot (f: the
  /// share escaped so far): (Σ Aᵢ ΔBᵢ / Σ Aᵢ)·(1 − f) / (1 − ρ̄(1 − f)); element i is displayed
  /// as Bᵢ + ρᵢ·ambient. withoutEmission: leave out
  /// the emission not yet shot (when the display takes direct light from rays, which already
  /// show its first bounce).
  glm::dvec3 ambient(bool withoutEmission = false) const;
  /// Patches that never shot so far (nothing, or too little, to send).
  int patchesNeverShot() const;
  /// Whether one channel is solved and copied to the others (a grey scene).
  bool grey() const { return grey_; }
  /// Hemicubes (factor computations) so far; shots reuse cached factors.
  long hemicubes() const { return cache_.computed(); }
  /// Memory the cached factors take.
  size_t cachedBytes() const { return cache_.bytes(); }

 private:
  /// Per element: B = ΔB = E, ρ, area and patch; the emitted power and the mean reflectance.
  void readElements();
  /// Per patch: its unshot power, and the running unshot total.
  void sumPatchUnshot();
  int pickShooter() const;
  /// The stop the options call for now (tolerance, shots, time), or Stop::None.
  Stop stopCondition() const;
  bool stepOnce();
  /// Shoots from the patch, or from the cluster above it that chooseCluster picks.
  void shoot(int patch);
  /// The cluster above the patch that sends the most unshot power per hemicube, if that is at
  /// least kClusterGain times what the patch alone would; else -1.
  int chooseCluster(int patch);
  /// Shooting points of a patch and of a cluster, counted once (SampleCounter).
  int patchCount(int patch);
  int clusterCount(int cluster);
  /// One shot: every sample of the shooter (its factors in cache slot `slot`) sends its share
  /// of the patches' unshot power.
  void shootFrom(int slot, Shooter shooter, const std::vector<ShooterSample>& samples,
                 const std::vector<int>& patches);
  /// The resolution of a shot of these patches (Shooter::resolution; options.followingResolution).
  int shotResolution(const Shooter& shooter, const std::vector<int>& patches);
  /// The power each sample sends (ω times its elements' unshot power), and the emission part
  /// of it.
  void samplePowers(const std::vector<ShooterSample>& samples, std::vector<glm::dvec3>& powers,
                    std::vector<glm::dvec3>& emitted) const;
  /// Delivers every sample's power through its cached factors, in sample order.
  void deliverSamples(int slot, const std::vector<glm::dvec3>& powers,
                      const std::vector<glm::dvec3>& emitted);
  /// The shooter keeps (1 − ω) of its unshot power.
  void keepRemainder(int patch);
  /// The ledger's unshot power, and now and then a fresh running total of it.
  void sumUnshot();
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
  std::vector<std::vector<ShooterSample>> samples_;  // per patch, once it shoots
  std::unique_ptr<const ShooterClusters> clusters_;  // null: every patch shoots alone
  std::vector<std::vector<ShooterSample>> clusterSamples_;
  std::vector<int> patchCounts_, clusterCounts_;     // -1: not counted yet (sized when first asked)
  std::vector<glm::dvec3> B_, dB_, rho_;
  std::vector<glm::dvec3> direct_, dE_;  // received from emission; emission not yet shot
  std::vector<double> area_;
  std::vector<int> patchOf_;
  std::vector<glm::dvec3> patchUnshot_;  // Σ A ΔB over the patch's elements
  std::vector<int> shotsOf_;             // per patch
  double unshotLuminance_ = 0, emittedLuminance_ = 0, powerShot_ = 0;
  glm::dvec3 sent_{0.0};  // power sent by all shots so far, per channel (the ambient's escaping share)
  double strongestShot_ = 0;  // the most unshot power a non-emitting shot sent so far (luminance)
  glm::dvec3 rhoMean_{0.0};
  double totalArea_ = 0;
  EnergyLedger ledger_;
  long shots_ = 0, clusterShots_ = 0, coarserShots_ = 0;
  Stop stop_ = Stop::None;
  std::chrono::steady_clock::time_point start_;
  double elapsed_ = 0;  // seconds spent constructing and in step(): not the caller's time between
  FactorCache cache_;  // each sample's factors (patches, then clusters), within options.factorCacheBytes
  bool grey_ = false;
};

/// True when every element's reflectance and emission are the same in all three channels:
/// one channel then carries the whole solution.
bool isGrey(const PatchMesh& mesh);

}  // namespace rad
