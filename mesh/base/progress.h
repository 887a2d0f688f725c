#pragma once
// What a long stage says of how far it has got: now and then a line such as "contact lines
// 1200/4100 (12 s)", handed to the sink a command installed for its thread (the command
// line: stderr). Without a sink (tests, benchmarks, the viewer) nothing is said. The sink is
// installed rather than passed down because the stages sit several calls below the pipeline
// (radiosity/solve.h) that the commands call.
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>

namespace rad {

/// A stage says nothing before it has run this long (seconds)...
constexpr double kProgressDelay = 2.0;
/// ...and then at most one line this often (seconds).
constexpr double kProgressInterval = 2.0;

/// Receives one progress line at a time, without a newline.
using ProgressSink = std::function<void(const std::string&)>;

/// Installs `sink` for the stages the calling thread runs while the scope lives; the sink
/// installed before comes back when it ends.
class ProgressScope {
 public:
  explicit ProgressScope(ProgressSink sink);
  ~ProgressScope();
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  ProgressSink previous_;
};

/// The calling thread's sink (empty: none), for a stage another thread runs on its behalf to
/// install there (a ProgressScope of its own).
ProgressSink currentProgressSink();

/// The progress of one stage of `total` steps, said on the thread's sink as
/// "<what> <done>/<total> (<seconds> s)" once the stage has run kProgressDelay seconds, then at
/// most every kProgressInterval seconds.
class StageProgress {
 public:
  StageProgress(std::string what, size_t total);

  /// Notes that `done` of the steps are done; says so when a line is due.
  void update(size_t done);

 private:
  using Clock = std::chrono::steady_clock;

  std::string what_;
  size_t total_;
  Clock::time_point start_, next_;
  bool silent_;
};

}  // namespace rad
