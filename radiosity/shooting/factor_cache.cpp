#include "radiosity/shooting/factor_cache.h"

#include "mesh/base/parallel.h"

namespace rad {
namespace {

/// Bytes one cached row takes (the per-patch arrays of rows are not counted: a few bytes per
/// sample).
size_t rowBytes(const FormFactors& f) {
  return sizeof(FormFactors) + f.elements.capacity() * sizeof(int) +
         f.factors.capacity() * sizeof(double);
}

}  // namespace

FactorCache::FactorCache(size_t slots, size_t budgetBytes) : rows_(slots), budget_(budgetBytes) {}

void FactorCache::compute(FactorSource& source, int slot, const Shooter& shooter,
                          const std::vector<ShooterSample>& samples, const std::vector<glm::dvec3>& powers) {
  auto& rows = rows_[slot];
  if (rows.empty()) rows.resize(samples.size());
  lastSlot_ = slot;
  made_.clear();
  for (size_t index = 0; index < samples.size(); ++index)
    if (powers[index] != glm::dvec3(0.0) && !rows[index].ready) made_.push_back(int(index));
  // Each worker uses its own hemicube; which worker takes a sample does not change its row.
  parallelFor(made_.size(), source.workers(), [&](size_t k, int worker) {
    const int index = made_[k];
    source.factors(shooter, index, samples[index], rows[index].factors, worker);
  });
  for (int index : made_) rows[index].ready = true;
  computed_ += long(made_.size());
}

void FactorCache::keepWithinBudget() {
  if (lastSlot_ < 0) return;
  auto& rows = rows_[lastSlot_];
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
