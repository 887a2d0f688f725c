#include "radiosity/factor_cache.h"

#include "mesh/parallel.h"

namespace rad {
namespace {

/// Bytes one cached row takes (the per-patch arrays of rows are not counted: a few bytes per
/// sample).
size_t rowBytes(const FormFactors& f) {
  return sizeof(FormFactors) + f.elements.capacity() * sizeof(int) +
         f.factors.capacity() * sizeof(double);
}

}  // namespace

FactorCache::FactorCache(size_t patches, size_t budgetBytes) : rows_(patches), budget_(budgetBytes) {}

void FactorCache::compute(FactorSource& source, int patch, const std::vector<ShooterSample>& samples,
                          const std::vector<glm::dvec3>& powers) {
  auto& rows = rows_[patch];
  if (rows.empty()) rows.resize(samples.size());
  lastPatch_ = patch;
  made_.clear();
  for (size_t index = 0; index < samples.size(); ++index)
    if (powers[index] != glm::dvec3(0.0) && !rows[index].ready) made_.push_back(int(index));
  // Each worker uses its own hemicube; which worker takes a sample does not change its row.
  parallelFor(made_.size(), source.workers(), [&](size_t k, int worker) {
    const int index = made_[k];
    source.factors(patch, index, samples[index], rows[index].factors, worker);
  });
  for (int index : made_) rows[index].ready = true;
  computed_ += long(made_.size());
}

void FactorCache::keepWithinBudget() {
  if (lastPatch_ < 0) return;
  auto& rows = rows_[lastPatch_];
  for (int index : made_) {
    rows[index].factors.elements.shrink_to_fit();
    rows[index].factors.factors.shrink_to_fit();
    size_t bytes = rowBytes(rows[index].factors);
    if (bytes_ + bytes <= budget_) {
      bytes_ += bytes;
    } else {
      rows[index] = SampleRow{};
    }
  }
  made_.clear();
}

}  // namespace rad
