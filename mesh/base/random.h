#pragma once
// Random numbers for the path tracer and the solver's jittered rays: SplitMix64 (Steele, Lea &
// Flood 2014), one 64-bit state, a sound generator for many independent streams whose seeds are
// themselves mixed.
#include <cstdint>

namespace rad {

/// The SplitMix64 finaliser: a bijective mix of 64 bits.
inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

struct Random {
  uint64_t state = 0;
  /// Stream `stream` of seed `seed`: deterministic, and unrelated to its neighbours.
  static Random stream(uint64_t seed, uint64_t stream) {
    return {mix64(mix64(seed) ^ (stream * 0xd1342543de82ef95ull + 1))};
  }
  /// Uniform in [0, 1), 53 bits.
  double next() {
    state += 0x9e3779b97f4a7c15ull;
    return double(mix64(state) >> 11) * 0x1.0p-53;
  }
};

}  // namespace rad
