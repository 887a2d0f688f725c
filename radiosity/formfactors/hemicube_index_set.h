#pragma once
// A set of indices below a fixed bound, taken out in ascending order: a bit per index plus a
// bit per word of them, so that taking out costs the words in use (and bound / 4096), not
// the bound.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rad {

class IndexSet {
 public:
  /// Empties the set and makes room for the indices [0, bound).
  void resize(size_t bound) {
    words_.assign((bound + 63) / 64, 0);
    summary_.assign((words_.size() + 63) / 64, 0);
  }

  /// Adds index i (< bound).
  void insert(uint32_t i) {
    words_[i >> 6] |= uint64_t(1) << (i & 63);
    summary_[i >> 12] |= uint64_t(1) << ((i >> 6) & 63);
  }

  /// Calls take(i) for every index in ascending order, emptying the set.
  template <class Take>
  void drain(const Take& take) {
    for (size_t s = 0; s < summary_.size(); ++s) {
      for (uint64_t used = summary_[s]; used; used &= used - 1) {
        const size_t w = s * 64 + size_t(__builtin_ctzll(used));
        for (uint64_t bits = words_[w]; bits; bits &= bits - 1)
          take(uint32_t(w * 64 + size_t(__builtin_ctzll(bits))));
        words_[w] = 0;
      }
      summary_[s] = 0;
    }
  }

 private:
  std::vector<uint64_t> words_, summary_;
};

}  // namespace rad
