#include "radiosity/progressive_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>

#include <glm/geometric.hpp>

#include "mesh/error.h"
#include "mesh/geometry.h"
#include "mesh/patch_mesh.h"

namespace rad {
namespace {

/// Recompute the running unshot total this often, so its round-off cannot drift.
constexpr long kResumEvery = 256;

/// A part of an element a shooter sample may take: `share` of the element's power.
struct Part {
  int element;
  double share, area;
  glm::dvec3 centroid;
  std::array<glm::dvec3, 3> corners;
};

/// Cuts triangle t into m² congruent triangles (each edge into m equal pieces).
void subdivide(int element, const std::array<glm::dvec3, 3>& t, int m, std::vector<Part>& out) {
  const double area = triangleArea(t[0], t[1], t[2]) / double(m * m), share = 1.0 / double(m * m);
  for (const auto& c : congruentSplit(t, m))
    out.push_back({element, share, area, (c[0] + c[1] + c[2]) / 3.0, c});
}

/// Splits `parts` into `strata` groups of about equal area: ordered along the longest axis of
/// their centroids' bounding box and cut where the running area best matches the share of the
/// first half of the strata; each half is split in turn.
void bisectByArea(std::vector<Part> parts, int strata, std::vector<std::vector<Part>>& out) {
  if (strata <= 1 || parts.size() <= 1) {
    out.push_back(std::move(parts));
    return;
  }
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const Part& p : parts) {
    lo = glm::min(lo, p.centroid);
    hi = glm::max(hi, p.centroid);
  }
  glm::dvec3 extent = hi - lo;
  int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  std::stable_sort(parts.begin(), parts.end(), [&](const Part& a, const Part& b) {
    return a.centroid[axis] < b.centroid[axis];
  });
  double total = 0;
  for (const Part& p : parts) total += p.area;
  const int first = strata / 2;
  const double target = total * first / strata;
  // Each side keeps at least as many parts as strata it must make, where it can.
  const size_t lowest = std::min<size_t>(first, parts.size() - 1);
  const size_t highest = std::max<size_t>(lowest, parts.size() - std::min<size_t>(strata - first, parts.size() - 1));
  size_t cut = lowest;
  double running = 0, best = HUGE_VAL;
  for (size_t i = 0; i < parts.size(); ++i) {
    running += parts[i].area;
    if (i + 1 >= lowest && i + 1 <= highest && std::abs(running - target) < best)
      best = std::abs(running - target), cut = i + 1;
  }
  std::vector<Part> tail(parts.begin() + long(cut), parts.end());
  parts.resize(cut);
  bisectByArea(std::move(parts), first, out);
  bisectByArea(std::move(tail), strata - first, out);
}

/// Where a stratum shoots from: its area-weighted centroid, or, should that fall outside its
/// parts (a stratum bent round a corner of the patch), the nearest part centroid.
glm::dvec3 stratumPoint(const std::vector<Part>& stratum, const glm::dvec3& normal) {
  glm::dvec3 centre(0.0);
  double area = 0;
  for (const Part& p : stratum) {
    centre += p.area * p.centroid;
    area += p.area;
  }
  centre /= area;
  glm::dvec3 nearest = stratum[0].centroid;
  for (const Part& p : stratum) {
    const auto& c = p.corners;
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside = inside && glm::dot(glm::cross(c[(k + 1) % 3] - c[k], centre - c[k]), normal) >= 0;
    if (inside) return centre;
    if (glm::length(p.centroid - centre) < glm::length(nearest - centre)) nearest = p.centroid;
  }
  return nearest;
}

}  // namespace

double EnergyLedger::residual() const {
  glm::dvec3 gap = emitted - absorbed - escaped - unshot;
  double worst = 0;
  for (int k = 0; k < 3; ++k)
    if (emitted[k] > 0) worst = std::max(worst, std::abs(gap[k]) / emitted[k]);
  return worst;
}

SampleCounter::SampleCounter(const PatchMesh& mesh, const SolverOptions& options)
    : mesh_(mesh), options_(options) {
  if (options.proximitySamples <= 0 || mesh.patches.empty()) return;
  double sum = 0;
  for (const Patch& p : mesh.patches) sum += p.diameter;
  cell_ = std::max(sum / double(mesh.patches.size()), 1e-300);
  for (int e = 0; e < mesh.elementCount(); ++e) grid_[key(cellOf(mesh.centroid(e)))].push_back(e);
}

std::array<int64_t, 3> SampleCounter::cellOf(const glm::dvec3& p) const {
  return {int64_t(std::floor(p.x / cell_)), int64_t(std::floor(p.y / cell_)),
          int64_t(std::floor(p.z / cell_))};
}

uint64_t SampleCounter::key(const std::array<int64_t, 3>& c) {
  return uint64_t(c[0]) * 73856093u ^ uint64_t(c[1]) * 19349663u ^ uint64_t(c[2]) * 83492791u;
}

int SampleCounter::operator()(int patch) const {
  const Patch& p = mesh_.patches[patch];
  if (mesh_.emits(patch)) return options_.emitterSamples;
  const int fewest = options_.shooterSamples;
  const int most = std::max(fewest, options_.emitterSamples);
  if (options_.proximitySamples <= 0) return fewest;
  // Only elements nearer than D·√(k / fewest) ask for more than the fewest points.
  const double reach = p.diameter * std::sqrt(options_.proximitySamples / fewest);
  double nearest = HUGE_VAL;
  const auto lo = cellOf(p.centroid - glm::dvec3(reach)), hi = cellOf(p.centroid + glm::dvec3(reach));
  for (int64_t x = lo[0]; x <= hi[0]; ++x)
    for (int64_t y = lo[1]; y <= hi[1]; ++y)
      for (int64_t z = lo[2]; z <= hi[2]; ++z) {
        auto it = grid_.find(key({x, y, z}));
        if (it == grid_.end()) continue;
        for (int e : it->second) {
          // An element of another plane facing the patch (occlusion ignored); hash
          // collisions only bring elements that fail the distance test.
          glm::dvec3 d = mesh_.centroid(e) - p.centroid;
          if (glm::dot(d, p.normal) <= 1e-9 * p.diameter || glm::dot(d, mesh_.normal(e)) >= 0) continue;
          nearest = std::min(nearest, glm::length(d));
        }
      }
  if (!(nearest < reach)) return fewest;
  const double ratio = p.diameter / nearest;
  const double wanted = std::ceil(options_.proximitySamples * ratio * ratio - 1e-9);
  return int(std::min<double>(std::max<double>(wanted, fewest), most));
}

bool isGrey(const PatchMesh& mesh) {
  auto same = [](const glm::dvec3& v) { return v.x == v.y && v.y == v.z; };
  for (int e = 0; e < mesh.elementCount(); ++e)
    if (!same(mesh.reflectance(e)) || !same(mesh.emission(e))) return false;
  return true;
}

std::vector<ShooterSample> patchSamples(const PatchMesh& mesh, int patch, int count) {
  const Patch& p = mesh.patches[patch];
  std::vector<Part> parts;
  for (int e : p.elements) {
    // Enough m×m parts that the patch has at least `count` of them, spread by area.
    double quota = double(count) * mesh.area(e) / p.area;
    int m = std::max(1, int(std::ceil(std::sqrt(quota) - 1e-9)));
    subdivide(e, mesh.corners(e), m, parts);
  }
  std::vector<std::vector<Part>> strata;
  bisectByArea(std::move(parts), count, strata);
  std::vector<ShooterSample> out;
  for (const auto& stratum : strata) {
    ShooterSample s;
    s.point = stratumPoint(stratum, p.normal);
    s.normal = p.normal;
    for (const Part& part : stratum) {
      if (!s.elements.empty() && s.elements.back() == part.element) {
        s.weights.back() += part.share;
        continue;
      }
      auto at = std::find(s.elements.begin(), s.elements.end(), part.element);
      if (at != s.elements.end()) {
        s.weights[size_t(at - s.elements.begin())] += part.share;
      } else {
        s.elements.push_back(part.element);
        s.weights.push_back(part.share);
      }
    }
    out.push_back(std::move(s));
  }
  return out;
}

HemicubeFactors::HemicubeFactors(const PatchMesh& mesh, int resolution, double sceneSize,
                                 unsigned seed, int workers, int emitterResolution)
    : mesh_(mesh), geometry_(HemicubeGeometry::fromMesh(mesh)), seed_(seed) {
  if (workers <= 0) workers = std::max(1, int(std::thread::hardware_concurrency()));
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

ProgressiveSolver::ProgressiveSolver(const PatchMesh& mesh, FactorSource& factors,
                                     const SolverOptions& options)
    : mesh_(mesh), factors_(factors), options_(options), counter_(mesh, options),
      start_(std::chrono::steady_clock::now()) {
  const int n = mesh.elementCount();
  B_.resize(n);
  dB_.resize(n);
  direct_.assign(n, glm::dvec3(0.0));
  dE_.resize(n);
  rho_.resize(n);
  area_.resize(n);
  patchOf_.resize(n);
  for (int e = 0; e < n; ++e) {
    B_[e] = dB_[e] = dE_[e] = mesh.emission(e);
    rho_[e] = mesh.reflectance(e);
    area_[e] = mesh.area(e);
    patchOf_[e] = mesh.patch(e);
    ledger_.emitted += area_[e] * B_[e];
    rhoMean_ += area_[e] * rho_[e];
    totalArea_ += area_[e];
  }
  rhoMean_ /= totalArea_;
  grey_ = isGrey(mesh);
  ledger_.unshot = ledger_.emitted;
  emittedLuminance_ = luminance(ledger_.emitted);
  patchUnshot_.assign(mesh.patches.size(), glm::dvec3(0.0));
  shotsOf_.assign(mesh.patches.size(), 0);
  samples_.resize(mesh.patches.size());
  rows_.resize(mesh.patches.size());
  for (size_t p = 0; p < mesh.patches.size(); ++p) {
    glm::dvec3 power(0.0);
    for (int e : mesh.patches[p].elements) power += area_[e] * dB_[e];
    patchUnshot_[p] = power;
    unshotLuminance_ += std::abs(luminance(power));
  }
  elapsed_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
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
  glm::dvec3 reflectionFactor = 1.0 / (1.0 - rhoMean_);
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
  elapsed_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return shot;
}

bool ProgressiveSolver::stepOnce() {
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
  auto& rows = rows_[patch];
  const auto& samples = samples_[patch];
  std::vector<int> todo;
  for (size_t index = 0; index < samples.size(); ++index)
    if (powers[index] != glm::dvec3(0.0) && !rows[index].ready) todo.push_back(int(index));
  // Workers take samples round-robin; each uses its own hemicube.
  auto work = [&](int worker, int stride) {
    for (size_t k = worker; k < todo.size(); k += stride)
      factors_.factors(patch, todo[k], samples[todo[k]], rows[todo[k]].factors, worker);
  };
  int workers = std::min<int>(factors_.workers(), int(todo.size()));
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) threads.emplace_back(work, w, workers);
  if (workers > 0) work(0, workers);
  for (auto& t : threads) t.join();
  for (int index : todo) rows[index].ready = true;
  hemicubes_ += long(todo.size());
}

namespace {

/// Bytes one cached row takes (the per-patch arrays of rows are not counted: a few bytes per
/// sample).
size_t rowBytes(const FormFactors& f) {
  return sizeof(FormFactors) + f.elements.capacity() * sizeof(int) +
         f.factors.capacity() * sizeof(double);
}

/// One channel of a triple (a grey scene's r stands for all three), or the triple itself.
template <class T>
T channels(const glm::dvec3& v);
template <>
double channels<double>(const glm::dvec3& v) { return v.x; }
template <>
glm::dvec3 channels<glm::dvec3>(const glm::dvec3& v) { return v; }

}  // namespace

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

void ProgressiveSolver::shoot(int patch) {
  const Patch& p = mesh_.patches[patch];
  if (samples_[patch].empty()) {
    samples_[patch] = patchSamples(mesh_, patch, counter_(patch));
  }
  // The power each element sends (ω times its unshot power) is fixed before any sample shoots.
  const double omega = options_.overshoot;
  const auto& samples = samples_[patch];
  // The emission part of the unshot power travels the same way and is also kept apart.
  std::vector<glm::dvec3> powers(samples.size(), glm::dvec3(0.0)), emitted(powers);
  for (size_t index = 0; index < samples.size(); ++index) {
    const ShooterSample& s = samples[index];
    for (size_t k = 0; k < s.elements.size(); ++k) {
      powers[index] += s.weights[k] * area_[s.elements[k]] * dB_[s.elements[k]];
      emitted[index] += s.weights[k] * area_[s.elements[k]] * dE_[s.elements[k]];
    }
    powers[index] *= omega;
    emitted[index] *= omega;
  }
  auto& rows = rows_[patch];
  if (rows.empty()) rows.resize(samples.size());
  std::vector<bool> wasReady(rows.size());
  for (size_t index = 0; index < rows.size(); ++index) wasReady[index] = rows[index].ready;
  computeFactors(patch, powers);
  // Deliver in sample order, so that the result does not depend on the workers.
  for (size_t index = 0; index < samples.size(); ++index) {
    const glm::dvec3& power = powers[index];
    if (power == glm::dvec3(0.0)) continue;
    const FormFactors& row = rows[index].factors;
    glm::dvec3 delivered = grey_ ? deliver<double>(power, row) : deliver<glm::dvec3>(power, row);
    if (emitted[index] != glm::dvec3(0.0)) deliverDirect(emitted[index], row);
    // What the hemicube did not deliver escaped (sky, back faces): the ledger closes exactly.
    ledger_.escaped += power - delivered;
    powerShot_ += std::abs(luminance(power));
  }
  // Keep the new rows while the budget allows; otherwise let them go.
  for (size_t index = 0; index < rows.size(); ++index) {
    if (wasReady[index] || !rows[index].ready) continue;
    rows[index].factors.elements.shrink_to_fit();
    rows[index].factors.factors.shrink_to_fit();
    size_t bytes = rowBytes(rows[index].factors);
    if (cachedBytes_ + bytes <= options_.factorCacheBytes) {
      cachedBytes_ += bytes;
    } else {
      rows[index] = SampleRow{};
    }
  }
  // The shooter keeps (1 − ω) of its unshot power: zero, or negative when overshooting.
  glm::dvec3 left(0.0);
  for (int e : p.elements) {
    dB_[e] *= (1 - omega);
    dE_[e] *= (1 - omega);
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
