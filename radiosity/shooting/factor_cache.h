#pragma once
// Form factors kept between a shooter's shots within a byte budget: a patch (or cluster)
// shooting again from the same points with the same rotations sees the same factors, and
// needs no hemicube.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "radiosity/shooting/factor_source.h"

namespace rad {

/// Per shooter (a slot: a patch, or a cluster after the patches), per sample: its form
/// factors, once computed, kept within the budget.
class FactorCache {
 public:
  /// Rows for `slots` shooters, kept while they take at most `budgetBytes` (0: none kept).
  FactorCache(size_t slots, size_t budgetBytes);

  /// Makes sure row(slot, i) holds sample i of `shooter`'s factors for every sample with power
  /// (powers[i] ≠ 0), computing the missing ones from `source` on its workers.
  void compute(FactorSource& source, int slot, const Shooter& shooter, const std::vector<ShooterSample>& samples,
               const std::vector<glm::dvec3>& powers);
  /// Sample `index` of the shooter in `slot`: its factors, once compute() has made them.
  const FormFactors& row(int slot, int index) const { return rows_[slot][index].factors; }
  /// Keeps the rows the last compute() made while the budget allows; lets the others go.
  void keepWithinBudget();

  /// Factor rows computed so far (hemicubes); rows taken from the cache are not counted.
  long computed() const { return computed_; }
  /// Memory the kept rows take.
  size_t bytes() const { return bytes_; }

 private:
  struct SampleRow {
    FormFactors factors;
    bool ready = false;
  };
  std::vector<std::vector<SampleRow>> rows_;  // per slot, per sample
  int lastSlot_ = -1;
  std::vector<int> made_;  // the samples whose rows the last compute() made, ascending
  size_t budget_, bytes_ = 0;
  long computed_ = 0;
};

}  // namespace rad
