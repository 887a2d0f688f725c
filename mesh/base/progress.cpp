#include "mesh/base/progress.h"

#include <cmath>
#include <utility>

namespace rad {
namespace {

/// The sink of the calling thread's stages (empty: silent).
ProgressSink& threadSink() {
  thread_local ProgressSink sink;
  return sink;
}

/// A duration in seconds as the clock's own.
std::chrono::steady_clock::duration after(double seconds) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

ProgressSink currentProgressSink() { return threadSink(); }

ProgressScope::ProgressScope(ProgressSink sink) : previous_(std::exchange(threadSink(), std::move(sink))) {}

ProgressScope::~ProgressScope() { threadSink() = std::move(previous_); }

StageProgress::StageProgress(std::string what, size_t total)
    : what_(std::move(what)), total_(total), start_(Clock::now()), next_(start_ + after(kProgressDelay)),
      silent_(!threadSink()) {}

void StageProgress::update(size_t done) {
  if (silent_) return;
  const Clock::time_point now = Clock::now();
  if (now < next_) return;
  next_ = now + after(kProgressInterval);
  const double seconds = std::chrono::duration<double>(now - start_).count();
  threadSink()(what_ + " " + std::to_string(done) + "/" + std::to_string(total_) + " (" +
               std::to_string(long(std::lround(seconds))) + " s)");
}

}  // namespace rad
