// Direct light ▸ which samples a point sees: rays to them, or, for a point between two ends,
// the ends' samples taken where they agree (some of those checked) and rays where they differ.
#include "radiosity/light/direct_light.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "radiosity/light/direct_light_internal.h"

namespace rad {
namespace {

/// A point between two ends that see different samples tests every this many-th of the
/// samples both ends see (and every sample they agree on, should one of those be hidden).
/// Only those: a convex occluder's shadow (from a sample) can hold the point between two ends
/// outside it, but not leave it out between two ends inside it. Measured (the Cornell box's
/// edges, tests/direct_light_test.cpp): every 12th of those both see, against every 8th of all
/// they agree on, half the checking rays and a smaller worst point (3.7 against 4.2 %); every
/// 16th of all let through a point twice as wrong.
constexpr size_t kAgreementCheck = 12;

/// The 64 bits of `bits` from bit j on (past its end: zeros).
uint64_t bitsFrom(const std::vector<uint64_t>& bits, size_t j) {
  const size_t word = j >> 6, shift = j & 63;
  const uint64_t low = bits[word] >> shift;
  return shift && word + 1 < bits.size() ? low | bits[word + 1] << (64 - shift) : low;
}

/// The bits of w as 0/1 chars at out[0, count), count ≤ 64, eight at a time (bit i of a byte
/// to byte i of a word, little-endian).
void unpackBits(uint64_t w, char* out, size_t count) {
  static const std::array<uint64_t, 256> bytes = [] {
    std::array<uint64_t, 256> t{};
    for (size_t b = 0; b < 256; ++b)
      for (size_t i = 0; i < 8; ++i) t[b] |= uint64_t(b >> i & 1) << (8 * i);
    return t;
  }();
  size_t k = 0;
  for (; k + 8 <= count; k += 8) std::memcpy(out + k, &bytes[(w >> k) & 255], 8);
  for (; k < count; ++k) out[k] = char(w >> k & 1);
}

/// samplesVisible's lists, one set per thread.
struct SampleLists {
  std::vector<glm::dvec3> to;
  std::vector<size_t> at, differing;
  std::vector<char> blocked;
};

}  // namespace

void DirectLight::samplesVisible(const Probe& probe, const glm::dvec3& origin, const std::vector<int>& samples,
                                 std::vector<char>& visible, long& raysCast) const {
  const size_t n = samples.size();
  visible.resize(n);
  thread_local SampleLists lists;
  SampleLists& l = lists;
  // Casts the rays to samples[k] for k in `which`; how many found other than `visible` held.
  auto cast = [&](const std::vector<size_t>& which) {
    l.to.clear();
    for (size_t k : which) l.to.push_back(points_[size_t(samples[k])]);
    rays_impl_->blocked(origin, l.to, l.blocked);
    raysCast += long(l.to.size());
    size_t changed = 0;
    for (size_t i = 0; i < which.size(); ++i) {
      const char seen = !l.blocked[i];
      changed += seen != visible[which[i]];
      visible[which[i]] = seen;
    }
    return changed;
  };
  if (!probe.visible) {
    l.at.resize(n);
    for (size_t k = 0; k < n; ++k) l.at[k] = k;
    cast(l.at);
    return;
  }
  // Consecutive samples (a light wholly above the horizon) are read 64 at a time.
  const bool run = direct_light::isRun(samples);
  const size_t first = run ? size_t(samples.front()) : 0;
  auto bit = [](const std::vector<uint64_t>& bits, int j) { return char(bits[size_t(j) >> 6] >> (size_t(j) & 63) & 1); };
  if (run)
    for (size_t k0 = 0; k0 < n; k0 += 64) unpackBits(bitsFrom(*probe.visible, first + k0), &visible[k0], std::min<size_t>(64, n - k0));
  else
    for (size_t k = 0; k < n; ++k) visible[k] = bit(*probe.visible, samples[k]);
  if (!probe.alsoVisible) return;
  // Between two ends that see different samples: rays to every kAgreementCheck-th of the
  // samples both see, and to those they do not agree on. A sample both ends see may still be
  // hidden from a point between them (past the corner of its shadow); should a checked one
  // be, every sample they agree on is tested.
  l.at.clear(), l.differing.clear();
  if (run) {
    size_t agreed = 0;  // before this word
    for (size_t k0 = 0; k0 < n; k0 += 64) {
      const uint64_t mask = n - k0 >= 64 ? ~uint64_t(0) : (uint64_t(1) << (n - k0)) - 1;
      const uint64_t differ = (bitsFrom(*probe.visible, first + k0) ^ bitsFrom(*probe.alsoVisible, first + k0)) & mask;
      for (uint64_t d = differ; d; d &= d - 1) l.differing.push_back(k0 + size_t(__builtin_ctzll(d)));
      // The samples both see of rank check, check + kAgreementCheck, ... in this word.
      uint64_t agree = ~differ & mask & bitsFrom(*probe.visible, first + k0);
      const size_t count = size_t(__builtin_popcountll(agree));
      size_t rank = agreed;  // of agree's lowest bit
      for (size_t check = (agreed + kAgreementCheck - 1) / kAgreementCheck * kAgreementCheck; check < agreed + count;
           check += kAgreementCheck) {
        for (; rank < check; ++rank) agree &= agree - 1;
        l.at.push_back(k0 + size_t(__builtin_ctzll(agree)));
      }
      agreed += count;
    }
  } else {
    size_t agreed = 0;
    for (size_t k = 0; k < n; ++k)
      if (bit(*probe.alsoVisible, samples[k]) != visible[k])
        l.differing.push_back(k);
      else if (visible[k] && agreed++ % kAgreementCheck == 0)
        l.at.push_back(k);
  }
  if (!l.at.empty() && cast(l.at) > 0) {  // contradicted: every other sample they agree on too
    size_t agreed = 0;
    for (size_t k = 0; k < n; ++k) {
      const char a = bit(*probe.visible, samples[k]), b = bit(*probe.alsoVisible, samples[k]);
      if (a == b && (!a || agreed++ % kAgreementCheck)) l.differing.push_back(k);
    }
  }
  if (!l.differing.empty()) cast(l.differing);
}

}  // namespace rad
