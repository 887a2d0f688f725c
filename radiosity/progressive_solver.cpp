#include "radiosity/progressive_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>

#include <glm/geometric.hpp>

#include "mesh/error.h"
#include "mesh/patch_mesh.h"

namespace rad {
namespace {

/// Overlaps below this share of an element are round-off at a part's edge.
constexpr double kNegligibleOverlap = 1e-12;
/// Recompute the running unshot total this often, so its round-off cannot drift.
constexpr long kResumEvery = 256;

/// The 4ᵏ triangles of k-fold midpoint subdivision of (a, b, c).
void subdivideTriangles(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int k,
                        std::vector<std::array<glm::dvec3, 3>>& out) {
  if (k == 0) {
    out.push_back({a, b, c});
    return;
  }
  glm::dvec3 ab = (a + b) * 0.5, bc = (b + c) * 0.5, ca = (c + a) * 0.5;
  subdivideTriangles(a, ab, ca, k - 1, out);
  subdivideTriangles(ab, b, bc, k - 1, out);
  subdivideTriangles(ca, bc, c, k - 1, out);
  subdivideTriangles(ab, bc, ca, k - 1, out);
}

/// Area of the part of the triangle `element` inside the coplanar triangle `part` (normal n):
/// the element clipped by the part's three edges (Sutherland–Hodgman).
double overlapArea(const std::array<glm::dvec3, 3>& element, const std::array<glm::dvec3, 3>& part,
                   const glm::dvec3& n) {
  std::vector<glm::dvec3> poly(element.begin(), element.end()), next;
  for (int k = 0; k < 3 && poly.size() >= 3; ++k) {
    glm::dvec3 a = part[k], inward = glm::cross(n, part[(k + 1) % 3] - a);
    next.clear();
    for (size_t i = 0; i < poly.size(); ++i) {
      const glm::dvec3 &p = poly[i], &q = poly[(i + 1) % poly.size()];
      double dp = glm::dot(p - a, inward), dq = glm::dot(q - a, inward);
      if (dp >= 0) next.push_back(p);
      if ((dp >= 0) != (dq >= 0)) next.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    poly.swap(next);
  }
  glm::dvec3 twice(0.0);
  for (size_t i = 1; i + 1 < poly.size(); ++i) twice += glm::cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
  return 0.5 * std::abs(glm::dot(twice, n));
}

}  // namespace

double EnergyLedger::residual() const {
  glm::dvec3 gap = emitted - absorbed - escaped - unshot;
  double worst = 0;
  for (int k = 0; k < 3; ++k)
    if (emitted[k] > 0) worst = std::max(worst, std::abs(gap[k]) / emitted[k]);
  return worst;
}

std::vector<ShooterSample> patchSamples(const PatchMesh& mesh, int patch, int minimum) {
  const Patch& p = mesh.patches[patch];
  const int n = int(p.elements.size());
  std::vector<ShooterSample> out;
  std::vector<std::array<glm::dvec3, 3>> parts;
  auto centroid = [](const std::array<glm::dvec3, 3>& t) { return (t[0] + t[1] + t[2]) / 3.0; };
  if (n < minimum) {
    int k = 0;
    while (n << (2 * k) < minimum) ++k;
    for (int e : p.elements) {
      auto c = mesh.corners(e);
      parts.clear();
      subdivideTriangles(c[0], c[1], c[2], k, parts);
      for (const auto& t : parts)
        out.push_back({{e}, {1.0 / double(parts.size())}, centroid(t), mesh.normal(e)});
    }
    return out;
  }
  int k = 0;
  while ((1 << (2 * k)) < minimum) ++k;
  subdivideTriangles(p.corners[0], p.corners[1], p.corners[2], k, parts);
  out.resize(parts.size());
  for (size_t i = 0; i < parts.size(); ++i) {
    out[i].point = centroid(parts[i]);
    out[i].normal = p.normal;
  }
  // Each element shares its power among the parts by overlap area, so that a uniform patch
  // shoots the same power from every part, and every element's weights sum to 1.
  const glm::dvec3 plane =
      glm::normalize(glm::cross(p.corners[1] - p.corners[0], p.corners[2] - p.corners[0]));
  std::vector<double> overlap(parts.size());
  for (int e : p.elements) {
    auto c = mesh.corners(e);
    double sum = 0;
    for (size_t i = 0; i < parts.size(); ++i) sum += overlap[i] = overlapArea(c, parts[i], plane);
    for (size_t i = 0; i < parts.size(); ++i) {
      if (!(overlap[i] > kNegligibleOverlap * sum)) continue;
      out[i].elements.push_back(e);
      out[i].weights.push_back(overlap[i] / sum);
    }
  }
  out.erase(std::remove_if(out.begin(), out.end(),
                           [](const ShooterSample& s) { return s.elements.empty(); }),
            out.end());
  return out;
}

HemicubeFactors::HemicubeFactors(const PatchMesh& mesh, int resolution, double sceneSize,
                                 unsigned seed, int workers)
    : mesh_(mesh), geometry_(HemicubeGeometry::fromMesh(mesh)), seed_(seed) {
  if (workers <= 0) workers = std::max(1, int(std::thread::hardware_concurrency()));
  for (int w = 0; w < workers; ++w)
    hemicubes_.push_back(std::make_unique<Hemicube>(geometry_, resolution, sceneSize));
}

void HemicubeFactors::factors(int patch, int index, const ShooterSample& sample,
                              FormFactors& out, int worker) {
  hemicubes_[worker]->compute(sample.point, sample.normal, hemicubeRotation(seed_, uint64_t(patch), uint64_t(index)),
                     out, mesh_.patches[patch].elements);
}

ProgressiveSolver::ProgressiveSolver(const PatchMesh& mesh, FactorSource& factors,
                                     const SolverOptions& options)
    : mesh_(mesh), factors_(factors), options_(options), start_(std::chrono::steady_clock::now()) {
  const int n = mesh.elementCount();
  B_.resize(n);
  dB_.resize(n);
  rho_.resize(n);
  area_.resize(n);
  patchOf_.resize(n);
  for (int e = 0; e < n; ++e) {
    B_[e] = dB_[e] = mesh.emission(e);
    rho_[e] = mesh.reflectance(e);
    area_[e] = mesh.area(e);
    patchOf_[e] = mesh.patch(e);
    ledger_.emitted += area_[e] * B_[e];
    rhoMean_ += area_[e] * rho_[e];
    totalArea_ += area_[e];
  }
  rhoMean_ /= totalArea_;
  ledger_.unshot = ledger_.emitted;
  emittedLuminance_ = luminance(ledger_.emitted);
  patchUnshot_.assign(mesh.patches.size(), glm::dvec3(0.0));
  shotsOf_.assign(mesh.patches.size(), 0);
  samples_.resize(mesh.patches.size());
  for (size_t p = 0; p < mesh.patches.size(); ++p) {
    glm::dvec3 power(0.0);
    for (int e : mesh.patches[p].elements) power += area_[e] * dB_[e];
    patchUnshot_[p] = power;
    unshotLuminance_ += std::abs(luminance(power));
  }
}

int ProgressiveSolver::patchesNeverShot() const {
  return int(std::count(shotsOf_.begin(), shotsOf_.end(), 0));
}

double ProgressiveSolver::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double ProgressiveSolver::unshotFraction() const {
  return emittedLuminance_ > 0 ? unshotLuminance_ / emittedLuminance_ : 0.0;
}

glm::dvec3 ProgressiveSolver::ambient() const {
  glm::dvec3 reflectionFactor = 1.0 / (1.0 - rhoMean_);
  return reflectionFactor * ledger_.unshot / totalArea_;
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
  if (unshotFraction() < options_.tolerance) stop_ = Stop::Tolerance;
  else if (options_.maxShots > 0 && shots_ >= options_.maxShots) stop_ = Stop::MaxShots;
  else if (options_.timeLimit > 0 && seconds() >= options_.timeLimit) stop_ = Stop::TimeLimit;
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

void ProgressiveSolver::computeFactors(int patch, const std::vector<glm::dvec3>& powers) {
  const auto& samples = samples_[patch];
  if (sampleFactors_.size() < samples.size()) sampleFactors_.resize(samples.size());
  // Workers take samples round-robin; each uses its own hemicube.
  auto work = [&](int worker, int stride) {
    for (size_t index = worker; index < samples.size(); index += stride)
      if (powers[index] != glm::dvec3(0.0))
        factors_.factors(patch, int(index), samples[index], sampleFactors_[index], worker);
  };
  int workers = std::min<int>(factors_.workers(), int(samples.size()));
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) threads.emplace_back(work, w, workers);
  work(0, workers);
  for (auto& t : threads) t.join();
}

void ProgressiveSolver::shoot(int patch) {
  const Patch& p = mesh_.patches[patch];
  if (samples_[patch].empty()) {
    bool emits = false;
    for (int e : p.elements) emits = emits || luminance(mesh_.emission(e)) > 0;
    samples_[patch] = patchSamples(mesh_, patch,
                                   emits ? options_.emitterSamples : options_.shooterSamples);
  }
  // The power each element sends (ω times its unshot power) is fixed before any sample shoots.
  const double omega = options_.overshoot;
  const auto& samples = samples_[patch];
  std::vector<glm::dvec3> powers(samples.size(), glm::dvec3(0.0));
  for (size_t index = 0; index < samples.size(); ++index) {
    const ShooterSample& s = samples[index];
    for (size_t k = 0; k < s.elements.size(); ++k)
      powers[index] += s.weights[k] * area_[s.elements[k]] * dB_[s.elements[k]];
    powers[index] *= omega;
  }
  computeFactors(patch, powers);
  // Deliver in sample order, so that the result does not depend on the workers.
  for (size_t index = 0; index < samples.size(); ++index) {
    const glm::dvec3& power = powers[index];
    if (power == glm::dvec3(0.0)) continue;
    const FormFactors& ff_ = sampleFactors_[index];
    glm::dvec3 delivered(0.0);
    for (size_t k = 0; k < ff_.elements.size(); ++k) {
      int j = ff_.elements[k];
      glm::dvec3 arriving = power * ff_.factors[k];
      glm::dvec3 reflected = rho_[j] * arriving;  // ρⱼ·ΔBᵢ·Fᵢⱼ·Aᵢ/Aⱼ per unit area of j
      delivered += arriving;
      ledger_.absorbed += arriving - reflected;
      if (reflected == glm::dvec3(0.0)) continue;  // black elements only absorb
      glm::dvec3 dB = reflected / area_[j];
      B_[j] += dB;
      dB_[j] += dB;
      int q = patchOf_[j];
      setPatchUnshot(q, patchUnshot_[q] + reflected);
    }
    // What the hemicube did not deliver escaped (sky, back faces): the ledger closes exactly.
    ledger_.escaped += power - delivered;
    powerShot_ += std::abs(luminance(power));
  }
  // The shooter keeps (1 − ω) of its unshot power: zero, or negative when overshooting.
  glm::dvec3 left(0.0);
  for (int e : p.elements) {
    dB_[e] *= (1 - omega);
    left += area_[e] * dB_[e];
  }
  setPatchUnshot(patch, left);
  ++shots_;
  ++shotsOf_[patch];
  // The ledger's unshot power and a fresh running total.
  ledger_.unshot = glm::dvec3(0.0);
  if (shots_ % kResumEvery == 0) unshotLuminance_ = 0;
  for (size_t q = 0; q < patchUnshot_.size(); ++q) {
    ledger_.unshot += patchUnshot_[q];
    if (shots_ % kResumEvery == 0) unshotLuminance_ += std::abs(luminance(patchUnshot_[q]));
  }
}

}  // namespace rad
