#include "mesh/base/stage_times.h"

#include <sys/resource.h>

#include <algorithm>

namespace rad {

StageTimes::Clock::time_point StageTimes::add(const std::string& name, Clock::time_point start) {
  const Clock::time_point now = Clock::now();
  add(name, std::chrono::duration<double>(now - start).count());
  return now;
}

void StageTimes::add(const std::string& name, double seconds) {
  auto it = std::find_if(stages_.begin(), stages_.end(), [&](const StageTime& s) { return s.name == name; });
  if (it == stages_.end()) it = stages_.insert(stages_.end(), StageTime{name, 0.0, 0.0});
  it->seconds += seconds;
  it->peakMiB = peakMiB();
}

void StageTimes::add(const StageTimes& other) {
  for (const StageTime& s : other.list()) {
    add(s.name, s.seconds);
    find(s.name).peakMiB = s.peakMiB;
  }
}

StageTime& StageTimes::find(const std::string& name) {
  return *std::find_if(stages_.begin(), stages_.end(), [&](const StageTime& s) { return s.name == name; });
}

double StageTimes::peakMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

double StageTimes::total() const {
  double sum = 0;
  for (const StageTime& s : stages_) sum += s.seconds;
  return sum;
}

double StageTimes::since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace rad
