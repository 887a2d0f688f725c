#pragma once
// How long each stage of a long computation took: `radiosity info` prints them and the solve
// report lists them ("stages"), so a user sees where the time of a large scene goes.
#include <chrono>
#include <string>
#include <vector>

namespace rad {

/// One stage, its wall time and the process's peak memory (MiB) when it last ended: where
/// the peak grows, that stage raised it.
struct StageTime {
  std::string name;
  double seconds = 0;
  double peakMiB = 0;
};

/// The stages of a computation in the order they first ran; a stage may run in several
/// spells (contact lines found and cut piece by piece), its times added up.
class StageTimes {
 public:
  using Clock = std::chrono::steady_clock;

  /// Adds the time since `start` to stage `name` and returns now, the next spell's start.
  Clock::time_point add(const std::string& name, Clock::time_point start);
  /// Adds `seconds` to stage `name`, appending the stage when it is new.
  void add(const std::string& name, double seconds);
  /// Appends the other's stages, adding to those of the same name.
  void add(const StageTimes& other);

  /// The process's peak resident memory so far, MiB.
  static double peakMiB();
  /// Wall-clock seconds since `start`.
  static double since(Clock::time_point start);

  const std::vector<StageTime>& list() const { return stages_; }
  /// The seconds of all stages together.
  double total() const;

 private:
  /// The stage of this name (it must be there).
  StageTime& find(const std::string& name);

  std::vector<StageTime> stages_;
};

}  // namespace rad
