#include "radiosity/shooting/progressive_solver.h"

#include <algorithm>
#include <cmath>

#include "mesh/base/error.h"
#include "mesh/patch_mesh.h"

namespace rad {
namespace {

/// Recompute the running unshot total this often, so its round-off cannot drift.
constexpr long kResumEvery = 256;
/// A cluster shoots instead of the patch picked if it sends at least this many times the power
/// per hemicube the patch would.
constexpr double kClusterGain = 2;

/// Seconds since `start`.
double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// One channel of a triple (a grey scene's r stands for all three), or the triple itself.
template <class T>
T channels(const glm::dvec3& v);
template <>
double channels<double>(const glm::dvec3& v) { return v.x; }
template <>
glm::dvec3 channels<glm::dvec3>(const glm::dvec3& v) { return v; }

/// The power a sample gathers from its elements: Σ weight · area · value.
glm::dvec3 weightedPower(const ShooterSample& s, const std::vector<double>& area, const std::vector<glm::dvec3>& value) {
  glm::dvec3 power(0.0);
  for (size_t k = 0; k < s.elements.size(); ++k) power += s.weights[k] * area[s.elements[k]] * value[s.elements[k]];
  return power;
}

}  // namespace

double EnergyLedger::residual() const {
  glm::dvec3 gap = emitted - absorbed - escaped - unshot;
  double worst = 0;
  for (int k = 0; k < 3; ++k)
    if (emitted[k] > 0) worst = std::max(worst, std::abs(gap[k]) / emitted[k]);
  return worst;
}

bool isGrey(const PatchMesh& mesh) {
  auto same = [](const glm::dvec3& v) { return v.x == v.y && v.y == v.z; };
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (!same(mesh.reflectance(e)) || !same(mesh.emission(e))) return false;
  return true;
}

int followingResolution(int R, double share) {
  auto even = [](double r) { return 2 * int(std::lround(r / 2)); };  // a hemicube's sides are R × R/2
  const int least = std::max(std::min(R, kLeastFollowingResolution), even(R / 2.0));
  // ∛share ≥ 2^(-1/4): R; ≥ 2^(-3/4): R/√2; below: R/2 (midpoints in log).
  const int wanted = share >= 0.5946 ? R : share >= 0.2102 ? even(R / std::sqrt(2.0)) : even(R / 2.0);
  return std::min(R, std::max(wanted, least));
}

ProgressiveSolver::ProgressiveSolver(const PatchMesh& mesh, FactorSource& factors,
                                     const SolverOptions& options)
    : mesh_(mesh), factors_(factors), options_(options), counter_(mesh, options),
      clusters_(options.clusters ? std::make_unique<const ShooterClusters>(mesh) : nullptr),
      start_(std::chrono::steady_clock::now()),
      cache_(mesh.patches.size() + (clusters_ ? size_t(clusters_->size()) : 0), options.factorCacheBytes) {
  readElements();
  grey_ = isGrey(mesh);
  ledger_.unshot = ledger_.emitted;
  emittedLuminance_ = luminance(ledger_.emitted);
  sumPatchUnshot();
  elapsed_ = since(start_);
}

void ProgressiveSolver::readElements() {
  const int n = mesh_.elementCount();
  B_.resize(n);
  dB_.resize(n);
  direct_.assign(n, glm::dvec3(0.0));
  dE_.resize(n);
  rho_.resize(n);
  area_.resize(n);
  patchOf_.resize(n);
  for (int e = 0; e < n; ++e) {
    B_[e] = dB_[e] = dE_[e] = mesh_.emission(e);
    rho_[e] = mesh_.reflectance(e);
    area_[e] = mesh_.area(e);
    patchOf_[e] = mesh_.patch(e);
    ledger_.emitted += area_[e] * B_[e];
    rhoMean_ += area_[e] * rho_[e];
    totalArea_ += area_[e];
  }
  rhoMean_ /= totalArea_;
}

void ProgressiveSolver::sumPatchUnshot() {
  const size_t patches = mesh_.patches.size();
  patchUnshot_.assign(patches, glm::dvec3(0.0));
  shotsOf_.assign(patches, 0);
  samples_.resize(patches);
  for (size_t p = 0; p < patches; ++p) {
    glm::dvec3 power(0.0);
    for (int e : mesh_.patches[p].elements) power += area_[e] * dB_[e];
    patchUnshot_[p] = power;
    unshotLuminance_ += std::abs(luminance(power));
  }
}

int ProgressiveSolver::patchesNeverShot() const {
  return int(std::count(shotsOf_.begin(), shotsOf_.end(), 0));
}

double ProgressiveSolver::seconds() const { return elapsed_; }

double ProgressiveSolver::unshotFraction() const {
  return emittedLuminance_ > 0 ? unshotLuminance_ / emittedLuminance_ : 0.0;
}

glm::dvec3 ProgressiveSolver::ambient(bool withoutEmission) const {
  glm::dvec3 unshot = ledger_.unshot;
  if (withoutEmission)
    for (size_t e = 0; e < dE_.size(); ++e) unshot -= area_[e] * dE_[e];
  // Of the power shot so far a share f escaped (the open side of a box, the sky); the unshot
  // power will fare alike: (1 − f) of it arrives, and (1 − f)·ρ̄ of each bounce comes back.
  // In a closed scene f = 0 and this is Cohen et al.'s 1 / (1 − ρ̄).
  glm::dvec3 kept(1.0);
  for (int c = 0; c < 3; ++c)
    if (sent_[c] > 0) kept[c] = 1 - std::clamp(ledger_.escaped[c] / sent_[c], 0.0, 1.0);
  const glm::dvec3 reflectionFactor = kept / (1.0 - rhoMean_ * kept);
  return reflectionFactor * unshot / totalArea_;
}

int ProgressiveSolver::pickShooter() const {
  int best = -1;
  double most = 0;
  for (size_t p = 0; p < patchUnshot_.size(); ++p) {
    double power = std::abs(luminance(patchUnshot_[p]));
    if (power > most) most = power, best = int(p);
  }
  return best;
}

void ProgressiveSolver::setPatchUnshot(int patch, const glm::dvec3& power) {
  unshotLuminance_ += std::abs(luminance(power)) - std::abs(luminance(patchUnshot_[patch]));
  patchUnshot_[patch] = power;
}

bool ProgressiveSolver::step() {
  if (stop_ != Stop::None) return false;
  const auto start = std::chrono::steady_clock::now();
  const bool shot = stepOnce();
  elapsed_ += since(start);
  return shot;
}

ProgressiveSolver::Stop ProgressiveSolver::stopCondition() const {
  if (unshotFraction() < options_.tolerance) return Stop::Tolerance;
  if (options_.maxShots > 0 && shots_ >= options_.maxShots) return Stop::MaxShots;
  if (options_.timeLimit > 0 && seconds() >= options_.timeLimit) return Stop::TimeLimit;
  return Stop::None;
}

bool ProgressiveSolver::stepOnce() {
  stop_ = stopCondition();
  if (stop_ != Stop::None) return false;
  int patch = pickShooter();
  if (patch < 0) {  // nothing left to shoot at all
    stop_ = Stop::Tolerance;
    return false;
  }
  shoot(patch);
  return true;
}

void ProgressiveSolver::run() {
  while (step()) {
  }
}

template <class T>
glm::dvec3 ProgressiveSolver::deliver(const glm::dvec3& power, const FormFactors& row) {
  const T sent = channels<T>(power);
  T arrived(0.0), absorbed(0.0);
  for (size_t k = 0; k < row.elements.size(); ++k) {
    const int j = row.elements[k];
    const T arriving = sent * row.factors[k];
    const T reflected = channels<T>(rho_[j]) * arriving;  // ρⱼ·ΔBᵢ·Fᵢⱼ·Aᵢ/Aⱼ per unit area of j
    arrived += arriving;
    absorbed += arriving - reflected;
    if (reflected == T(0.0)) continue;  // black elements only absorb
    const glm::dvec3 dB(reflected / area_[j]);
    B_[j] += dB;
    dB_[j] += dB;
    const int q = patchOf_[j];
    setPatchUnshot(q, patchUnshot_[q] + glm::dvec3(reflected));
  }
  ledger_.absorbed += glm::dvec3(absorbed);
  return glm::dvec3(arrived);
}

void ProgressiveSolver::deliverDirect(const glm::dvec3& power, const FormFactors& row) {
  for (size_t k = 0; k < row.elements.size(); ++k) {
    const int j = row.elements[k];
    direct_[j] += rho_[j] * power * (row.factors[k] / area_[j]);
  }
}

void ProgressiveSolver::samplePowers(const std::vector<ShooterSample>& samples, std::vector<glm::dvec3>& powers,
                                     std::vector<glm::dvec3>& emitted) const {
  const double omega = options_.overshoot;
  powers.assign(samples.size(), glm::dvec3(0.0));
  emitted = powers;
  for (size_t index = 0; index < samples.size(); ++index) {
    const ShooterSample& s = samples[index];
    powers[index] = weightedPower(s, area_, dB_);
    emitted[index] = weightedPower(s, area_, dE_);
    powers[index] *= omega;
    emitted[index] *= omega;
  }
}

void ProgressiveSolver::deliverSamples(int slot, const std::vector<glm::dvec3>& powers,
                                       const std::vector<glm::dvec3>& emitted) {
  // Sample order, so that the result does not depend on the workers.
  for (size_t index = 0; index < powers.size(); ++index) {
    const glm::dvec3& power = powers[index];
    if (power == glm::dvec3(0.0)) continue;
    const FormFactors& row = cache_.row(slot, int(index));
    glm::dvec3 delivered = grey_ ? deliver<double>(power, row) : deliver<glm::dvec3>(power, row);
    if (emitted[index] != glm::dvec3(0.0)) deliverDirect(emitted[index], row);
    // What the hemicube did not deliver escaped (sky, back faces): the ledger closes exactly.
    ledger_.escaped += power - delivered;
    powerShot_ += std::abs(luminance(power));
    sent_ += power;
  }
}

void ProgressiveSolver::keepRemainder(int patch) {
  // Zero, or negative when overshooting.
  const double omega = options_.overshoot;
  glm::dvec3 left(0.0);
  for (int e : mesh_.patches[patch].elements) {
    dB_[e] *= (1 - omega);
    dE_[e] *= (1 - omega);
    left += area_[e] * dB_[e];
  }
  setPatchUnshot(patch, left);
}

void ProgressiveSolver::sumUnshot() {
  ledger_.unshot = glm::dvec3(0.0);
  if (shots_ % kResumEvery == 0) unshotLuminance_ = 0;
  for (size_t q = 0; q < patchUnshot_.size(); ++q) {
    ledger_.unshot += patchUnshot_[q];
    if (shots_ % kResumEvery == 0) unshotLuminance_ += std::abs(luminance(patchUnshot_[q]));
  }
}

int ProgressiveSolver::patchCount(int patch) {
  if (patchCounts_.empty()) patchCounts_.assign(mesh_.patches.size(), -1);
  int& count = patchCounts_[size_t(patch)];
  if (count < 0) count = counter_(patch);
  return count;
}

int ProgressiveSolver::clusterCount(int cluster) {
  if (clusterCounts_.empty()) clusterCounts_.assign(size_t(clusters_->size()), -1);
  int& count = clusterCounts_[size_t(cluster)];
  if (count < 0) count = counter_((*clusters_)[cluster]);
  return count;
}

int ProgressiveSolver::chooseCluster(int patch) {
  if (!clusters_) return -1;
  // Power sent per hemicube: the patch alone, and each cluster above it. Most patches of a
  // scene never shoot before the tolerance is met, so a cluster pays only by sending more
  // per hemicube than the patch picked would.
  const double alone = std::abs(luminance(patchUnshot_[size_t(patch)])) / patchCount(patch);
  int best = -1;
  double bestRate = kClusterGain * alone;
  for (int c = clusters_->above(patch); c >= 0; c = (*clusters_)[c].parent) {
    double power = 0;
    for (int q : (*clusters_)[c].patches) power += std::abs(luminance(patchUnshot_[size_t(q)]));
    // Cheap first: at more points than this it could not do better.
    if (!(power >= bestRate)) continue;
    const int together = clusterCount(c);
    if (power / together >= bestRate) best = c, bestRate = power / together;
  }
  return best;
}

void ProgressiveSolver::shoot(int patch) {
  const int cluster = chooseCluster(patch);
  if (cluster >= 0) {
    if (clusterSamples_.empty()) clusterSamples_.resize(size_t(clusters_->size()));
    auto& samples = clusterSamples_[size_t(cluster)];
    const ShooterCluster& c = (*clusters_)[cluster];
    if (samples.empty()) samples = clusterSamples(mesh_, c, clusterCount(cluster));
    RAD_CHECK(!samples.empty());
    shootFrom(int(mesh_.patches.size()) + cluster, Shooter{c.patches.front(), cluster, &c.elements}, samples,
              c.patches);
    ++clusterShots_;
    return;
  }
  if (samples_[patch].empty()) samples_[patch] = patchSamples(mesh_, patch, patchCount(patch));
  shootFrom(patch, Shooter{patch}, samples_[patch], {patch});
}

int ProgressiveSolver::shotResolution(const Shooter& shooter, const std::vector<int>& patches) {
  if (options_.followingResolution <= 0 || (shooter.cluster < 0 && mesh_.emits(shooter.patch))) return 0;
  double power = 0;
  for (int p : patches) power += std::abs(luminance(patchUnshot_[size_t(p)]));
  strongestShot_ = std::max(strongestShot_, power);
  return followingResolution(options_.followingResolution, strongestShot_ > 0 ? power / strongestShot_ : 1);
}

void ProgressiveSolver::shootFrom(int slot, Shooter shooter, const std::vector<ShooterSample>& samples,
                                  const std::vector<int>& patches) {
  // The power each element sends (ω times its unshot power) is fixed before any sample
  // shoots; the emission part of it travels the same way and is also kept apart.
  std::vector<glm::dvec3> powers, emitted;
  samplePowers(samples, powers, emitted);
  shooter.resolution = shotResolution(shooter, patches);
  const long drawn = cache_.computed();
  cache_.compute(factors_, slot, shooter, samples, powers);
  coarserShots_ += cache_.computed() > drawn && shooter.resolution > 0 && shooter.resolution < options_.followingResolution;
  deliverSamples(slot, powers, emitted);
  // Keep the new rows while the budget allows; otherwise let them go.
  cache_.keepWithinBudget();
  for (int p : patches) {
    keepRemainder(p);
    ++shotsOf_[p];
  }
  ++shots_;
  sumUnshot();
}

}  // namespace rad
