// Direct light ▸ the light at a point: its lights share its rays by what each brings, a light
// in whose penumbra it lies is tested again, and a light seen in part is weighed sample by sample.
#include "radiosity/light/direct_light.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "mesh/base/color.h"
#include "mesh/base/parallel.h"
#include "mesh/base/progress.h"
#include "mesh/scene/geometry.h"
#include "radiosity/formfactors/point_polygon.h"
#include "radiosity/light/clear_sight.h"
#include "radiosity/light/direct_light_internal.h"

namespace rad {
namespace {

/// Sets bit samples[k] of `bits` where visible[k] (consecutive samples 64 at a time).
void setBits(const std::vector<int>& samples, const std::vector<char>& visible, std::vector<uint64_t>& bits) {
  const size_t n = samples.size();
  if (n == 0) return;
  if (!direct_light::isRun(samples)) {
    for (size_t k = 0; k < n; ++k) bits[size_t(samples[k]) >> 6] |= uint64_t(visible[k]) << (size_t(samples[k]) & 63);
    return;
  }
  for (size_t k0 = 0; k0 < n; k0 += 64) {
    uint64_t w = 0;
    for (size_t k = k0; k < std::min(n, k0 + 64); ++k) w |= uint64_t(visible[k]) << (k - k0);
    const size_t j = size_t(samples[k0]), word = j >> 6, shift = j & 63;
    bits[word] |= w << shift;
    if (shift && w >> (64 - shift)) bits[word + 1] |= w >> (64 - shift);
  }
}

/// The stride through a light's samples above a point's horizon (`above` of them) for the
/// light's `share` of the point's light: a power of two leaving at least raysPerPoint·share
/// samples, and never fewer than kMinRaysPerLight.
size_t sampleStride(size_t above, double share, int raysPerPoint) {
  const double wanted = std::max(double(kMinRaysPerLight), raysPerPoint * share);
  size_t stride = 1;
  while (double(above) / double(2 * stride) >= wanted) stride *= 2;
  return stride;
}

}  // namespace

/// One light as a point sees it: its samples above the point's horizon and which are visible.
/// Every stride-th sample is tested by a ray; consecutive samples are neighbouring strata
/// (patchSamples bisects by area), so each tested one stands for the stride of them from it.
/// A light seen partly counts each visible sample by its own differential factor
/// cosθ·cosθ'/r² (samples stand for equal areas, so that near a light its close parts count
/// more); those are weighed only then, as a light seen whole or not at all needs no weights.
struct DirectLight::SeenLight {
  std::vector<int> above;
  std::vector<char> visible;  ///< per sample above, tested or taken from the tested one before it
  std::vector<double> weight; ///< per sample above, once weighed
  double F = 0;               ///< the light's exact unoccluded factor
  double share = -1;          ///< the visible share of its weight, once found (-1: not yet)
  size_t stride = 0;          ///< 0: nothing tested yet

  /// Every sample visible, as if each were tested (nothing stands between point and light).
  void seeWhole() {
    visible.assign(above.size(), 1);
    stride = 1;
    share = -1;
  }
  /// How many samples are visible (tested, or taken from a tested one).
  size_t seen() const { return size_t(std::count(visible.begin(), visible.end(), char(1))); }
  /// Whether some tested samples are visible and some not (the point is in its penumbra).
  bool partial() const {
    const size_t n = seen();
    return n > 0 && n < visible.size();
  }
};

double DirectLight::unoccludedFactor(const glm::dvec3& p, const glm::dvec3& n, size_t t) const {
  const LightPolygon& light = lights_[t];
  if (glm::dot(light.normal, p - light.outlines[0][0]) <= 0) return 0;  // behind the emitter
  const double F = pointRegionFormFactor(p, n, light.outlines);
  return F > 0 ? F : 0;
}

namespace {

/// A light is taken to lie wholly above a point's horizon, and the point wholly in front of
/// it, when every corner of its hull is above by this share of its distance, plus
/// kPlanarSlack of the light's size, at least: then every sample is, whatever the rounding
/// (samples lie inside the hull but for a piece's planarity tolerance).
constexpr double kWhollyAbove = 1e-9;
constexpr double kPlanarSlack = 4 * kPlanarity;

}  // namespace

bool DirectLight::whollyAbove(const glm::dvec3& p, const glm::dvec3& n, size_t t) const {
  const LightPolygon& light = lights_[t];
  bool whole = true;
  for (const glm::dvec3& c : light.hull) {
    const glm::dvec3 d = c - p;
    const double margin = kWhollyAbove * glm::length(d) + kPlanarSlack * light.size;
    whole = whole && glm::dot(n, d) > margin && -glm::dot(light.normal, d) > margin;
  }
  return whole;
}

void DirectLight::samplesAbove(const glm::dvec3& p, const glm::dvec3& n, size_t t, SeenLight& out) const {
  out.above.clear(), out.weight.clear(), out.visible.clear();
  out.stride = 0, out.share = -1;
  const LightPolygon& light = lights_[t];
  out.F = unoccludedFactor(p, n, t);
  if (!(out.F > 0)) return;
  if (whollyAbove(p, n, t)) {
    out.above.resize(size_t(light.count));
    for (int k = 0; k < light.count; ++k) out.above[size_t(k)] = light.first + k;
  } else {
    for (int j = light.first; j < light.first + light.count; ++j) {
      const glm::dvec3 d = onLight_[size_t(j)] - p;
      // Below the horizon, or behind the light.
      if (glm::dot(n, d) <= 0 || -glm::dot(light.normal, d) <= 0) continue;
      out.above.push_back(j);
    }
  }
  out.visible.assign(out.above.size(), 0);
}

double DirectLight::seenShare(const glm::dvec3& p, const glm::dvec3& n, size_t t, SeenLight& light) const {
  if (light.share >= 0) return light.share;
  const size_t seen = light.seen();
  if (seen == light.visible.size()) return light.share = 1;  // the weighted sum over all, exactly
  if (seen == 0) return light.share = 0;
  if (light.weight.empty()) {
    const glm::dvec3& ln = lights_[t].normal;
    const size_t m = light.above.size();
    light.weight.resize(m);
    double* weight = light.weight.data();
    // Axis by axis over a run of samples (a light wholly above the horizon), in the order of
    // glm::dot's terms (the same weights as point by point while the compiler contracts no
    // multiply-add, as at the default x86-64 target), so that the loop is vectorised.
    if (direct_light::isRun(light.above)) {
      const size_t first = size_t(light.above[0]);
      const double *x = onLightAxes_[0].data() + first, *y = onLightAxes_[1].data() + first,
                   *z = onLightAxes_[2].data() + first;
      for (size_t k = 0; k < m; ++k) {
        const double dx = x[k] - p.x, dy = y[k] - p.y, dz = z[k] - p.z;
        const double r2 = dx * dx + dy * dy + dz * dz, cosHere = n.x * dx + n.y * dy + n.z * dz;
        const double cosThere = -(ln.x * dx + ln.y * dy + ln.z * dz);
        weight[k] = cosHere * cosThere / (r2 * r2);
      }
    } else {
      for (size_t k = 0; k < m; ++k) {
        const glm::dvec3 d = onLight_[size_t(light.above[k])] - p;
        const double r2 = glm::dot(d, d), cosHere = glm::dot(n, d), cosThere = -glm::dot(ln, d);
        weight[k] = cosHere * cosThere / (r2 * r2);
      }
    }
  }
  double sum = 0, all = 0;
  for (size_t k = 0; k < light.above.size(); ++k) {
    all += light.weight[k];
    sum += light.weight[k] * double(light.visible[k]);
  }
  return light.share = all > 0 ? sum / all : 0.0;
}

void DirectLight::test(const Probe& probe, const glm::dvec3& p, size_t stride, SeenLight& light,
                       long& raysCast) const {
  if (light.stride && light.stride <= stride) return;
  if (!light.stride && stride == 1) {  // every sample, none tested yet: straight in
    samplesVisible(probe, p, light.above, light.visible, raysCast);
    light.stride = 1;
    light.share = -1;
    return;
  }
  thread_local std::vector<int> samples;
  thread_local std::vector<size_t> at;
  thread_local std::vector<char> visible;
  samples.clear(), at.clear();
  for (size_t k = 0; k < light.above.size(); k += stride)
    if (!light.stride || k % light.stride) samples.push_back(light.above[k]), at.push_back(k);
  samplesVisible(probe, p, samples, visible, raysCast);
  for (size_t i = 0; i < at.size(); ++i) light.visible[at[i]] = visible[i];
  light.stride = stride;
  light.share = -1;
  if (stride > 1)
    for (size_t k = 0; k < light.above.size(); ++k)
      if (k % stride) light.visible[k] = light.visible[k - k % stride];
}

namespace {

/// How many of the bits [first, first + count) of the words word(0), word(1), ... are set.
template <class Word>
size_t bitsSetIn(int first, int count, const Word& word) {
  size_t set = 0;
  for (int j = first; j < first + count;) {
    const int at = j / 64, from = j % 64, to = std::min(64, from + (first + count - j));
    uint64_t w = word(size_t(at)) >> from;
    if (to - from < 64) w &= (uint64_t(1) << (to - from)) - 1;
    set += size_t(__builtin_popcountll(w));
    j += to - from;
  }
  return set;
}

size_t bitsSet(const std::vector<uint64_t>& bits, int first, int count) {
  return bitsSetIn(first, count, [&](size_t w) { return bits[w]; });
}

/// How many of the bits [first, first + count) differ between a and b.
size_t bitsDiffer(const std::vector<uint64_t>& a, const std::vector<uint64_t>& b, int first, int count) {
  return bitsSetIn(first, count, [&](size_t w) { return a[w] ^ b[w]; });
}

}  // namespace

bool DirectLight::fromEnds(const Probe& probe, const glm::dvec3& p, VertexLight& out) const {
  struct Seen {
    double F;
    bool all;
  };
  thread_local std::vector<Seen> seen;
  seen.assign(lights_.size(), {0.0, false});
  for (size_t t = 0; t < lights_.size(); ++t) {
    const LightPolygon& light = lights_[t];
    // A penumbra is weighed sample by sample (compute): told first, before any factor.
    const size_t set = bitsSet(*probe.visible, light.first, light.count);
    if (set != 0 && set != size_t(light.count)) return false;
    const double F = unoccludedFactor(p, probe.normal, t);
    if (!(F > 0)) continue;
    if (!whollyAbove(p, probe.normal, t)) return false;  // some samples below the horizon
    seen[t] = {F, set != 0};
  }
  for (size_t t = 0; t < lights_.size(); ++t) {
    const LightPolygon& light = lights_[t];
    if (!(seen[t].F > 0)) continue;
    const glm::dvec3 full = probe.rho * light.emission * seen[t].F;
    if (seen[t].all) {
      out.radiosity += full;
      for (int j = light.first; j < light.first + light.count; ++j) out.visible[size_t(j) >> 6] |= uint64_t(1) << (j & 63);
    }
    out.weight[t] = float(luminance(full) / double(light.count));
  }
  return true;
}

VertexLight DirectLight::compute(const Probe& probe, long& raysCast, long& seenWhole) const {
  VertexLight out;
  out.visible.assign(size_t((samples_ + 63) / 64), 0);
  out.weight.assign(lights_.size(), 0.0f);
  if (probe.rho == glm::dvec3(0.0)) return out;  // black: nothing to show
  const glm::dvec3 p = offSurface(probe, sceneSize_), &n = probe.normal;
  // Between two ends that see the same samples, each light seen whole or not at all: its
  // light at once, as the samples would give it.
  if (probe.visible && !probe.alsoVisible && fromEnds(probe, p, out)) return out;
  // Each light's samples above the horizon and its unoccluded light first: the lights share
  // the point's rays by what each brings (a probe given its visibility casts none).
  thread_local std::vector<SeenLight> seen;  // reused from probe to probe: no allocation
  thread_local std::vector<double> lum;
  seen.resize(lights_.size()), lum.assign(lights_.size(), 0.0);
  double open = 0;
  for (size_t t = 0; t < lights_.size(); ++t) {
    samplesAbove(p, n, t, seen[t]);
    if (!seen[t].above.empty()) open += lum[t] = luminance(lights_[t].emission) * seen[t].F;
  }
  if (!(open > 0)) return out;
  auto stride = [&](size_t t, double total) {
    return probe.visible ? 1 : sampleStride(seen[t].above.size(), lum[t] / total, raysPerPoint_);
  };
  double shown = 0;
  for (size_t t = 0; t < lights_.size(); ++t) {
    if (seen[t].above.empty()) continue;
    const size_t s = stride(t, open);
    // Clear sight is looked for where it would save many rays: a point given its ends'
    // samples casts them where those differ (many on an edge across a whole penumbra).
    const LightPolygon& light = lights_[t];
    const size_t rays = !probe.visible       ? seen[t].above.size() / s
                        : probe.alsoVisible ? bitsDiffer(*probe.visible, *probe.alsoVisible, light.first, light.count)
                                            : 0;
    if (probe.clearSight && rays >= size_t(kClearSightRays) && clearSight_->clear(p, light.rayHull)) {
      seen[t].seeWhole();
      ++seenWhole;
    } else {
      test(probe, p, s, seen[t], raysCast);
    }
    shown += lum[t] * seenShare(p, n, t, seen[t]);
  }
  // In a shadow the light that arrives is not what the open sky would bring: a light in
  // whose penumbra the point lies is tested again for its share of what is shown.
  for (size_t t = 0; t < lights_.size() && shown > 0; ++t)
    if (seen[t].stride > 1 && seen[t].partial()) test(probe, p, stride(t, shown), seen[t], raysCast);
  for (size_t t = 0; t < lights_.size(); ++t) {
    SeenLight& light = seen[t];
    if (light.above.empty()) continue;
    setBits(light.above, light.visible, out.visible);
    const glm::dvec3 full = probe.rho * lights_[t].emission * light.F;
    out.radiosity += full * seenShare(p, n, t, light);
    out.weight[t] = float(luminance(full) / double(light.above.size()));  // the mean sample's share
  }
  return out;
}

std::vector<VertexLight> DirectLight::lightAt(const std::vector<Probe>& probes) {
  std::vector<VertexLight> out(probes.size());
  if (!enabled_) return out;
  // Rays per worker, each count on its own cache line: counted per ray, they would otherwise
  // bounce one line between the cores.
  struct alignas(64) Count {
    long rays = 0, whole = 0;
  };
  std::vector<Count> cast(static_cast<size_t>(workers_));
  StageProgress progress("direct light: points", probes.size());  // said by the caller's worker
  parallelFor(
      probes.size(), workers_,
      [&](size_t k, int worker) {
        if (worker == 0) progress.update(k);
        out[k] = compute(probes[k], cast[size_t(worker)].rays, cast[size_t(worker)].whole);
      },
      64);
  for (const Count& c : cast) rays_ += c.rays, seenWhole_ += c.whole;
  return out;
}

}  // namespace rad
