#pragma once
// Groups of 0..n−1 joined pair by pair (union-find with path halving).
#include <cstddef>
#include <numeric>
#include <vector>

namespace rad {

class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), size_t(0)); }
  /// The representative of i's group.
  size_t find(size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(size_t a, size_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<size_t> parent_;
};

}  // namespace rad
