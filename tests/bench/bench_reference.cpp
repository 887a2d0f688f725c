// The independent reference's speed on the Cornell box: paths per second on one core, and
// the whole default reference (300 points at 1 % standard error) on every core.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/pathtrace/path_tracer.h"

using namespace rad;
using namespace rad::pathtrace;

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// One core: a fixed number of paths at every point.
void benchOneCore(const TraceScene& traced, const std::vector<SurfacePoint>& points) {
  TraceOptions options;
  options.paths = 20'000;
  options.workers = 1;
  const PathTracer tracer(traced);
  const auto t0 = std::chrono::steady_clock::now();
  tracer.estimate(points, options);
  const double s = since(t0);
  std::printf("one core: %ld paths in %.2f s: %.3g paths per second\n", tracer.pathsTraced(), s,
              double(tracer.pathsTraced()) / s);
}

/// The default reference: until SE/B < 1 % in every channel, all cores.
void benchDefaultReference(const TraceScene& traced, const std::vector<SurfacePoint>& points) {
  TraceOptions options;
  const PathTracer tracer(traced);
  const auto t0 = std::chrono::steady_clock::now();
  const auto estimates = tracer.estimate(points, options);
  const double s = since(t0);
  double worst = 0;
  for (const auto& e : estimates)
    for (int c = 0; c < 3; ++c)
      if (e.B[c] > 0) worst = std::max(worst, e.standardError[c] / e.B[c]);
  std::printf("300 points at 1 %% SE, all cores: %ld paths in %.2f s (%.3g per second), worst SE/B %.4f\n",
              tracer.pathsTraced(), s, double(tracer.pathsTraced()) / s, worst);
}

}  // namespace

int main() {
  const Scene scene = loadScene(std::string(RAD_SOURCE_DIR) + "/scenes/cornell.json");
  const TraceScene traced(scene);
  const auto points = placePoints(traced, 300, 1);
  benchOneCore(traced, points);
  benchDefaultReference(traced, points);
}
