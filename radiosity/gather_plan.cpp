#include "radiosity/gather_plan.h"

#include <algorithm>
#include <cstdio>

#include "mesh/base/parallel.h"

namespace rad {

std::string gatherLeftOut(const GatherEstimate& estimate, int workers, double timeLeft, double timeLimit) {
  const double seconds = estimate.seconds(workers), oneCore = estimate.seconds(1);
  char text[320];
  if (timeLeft > 0 && timeLeft <= kNoTimeLeft)
    std::snprintf(text, sizeof text,
                  "final gather skipped, and no shot: meshing took all of the %.3g s time limit; the direct light "
                  "and the ambient term are shown",
                  timeLimit);
  else if (oneCore > kMaxGatherSeconds)
    std::snprintf(text, sizeof text,
                  "final gather skipped: its hemicubes would take about %.2g s on one core, more than the %.0f s "
                  "it may (a quarter of an hour on two); the progressive solution is shown at the vertices (coarser "
                  "elements gather: raise solver.max_element_edge)",
                  oneCore, kMaxGatherSeconds);
  else if (timeLeft > 0 && seconds > kGatherShareOfTimeLeft * timeLeft)
    std::snprintf(text, sizeof text,
                  "final gather skipped: it would take about %.2g s of the %.2g s the time limit leaves after "
                  "meshing; the progressive solution is shown at the vertices, shot until the time limit",
                  seconds, timeLeft);
  else
    return {};
  return text;
}

GatherOptions gatherOptions(const Settings& settings, std::chrono::steady_clock::time_point started) {
  GatherOptions options;
  options.resolution = settings.gatherResolution;
  options.accuracy = settings.gatherAccuracy;
  options.elementEdge = settings.maxElementEdge;
  options.seed = settings.seed;
  if (settings.timeLimit > 0)
    options.deadline = started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                     std::chrono::duration<double>(settings.timeLimit));
  return options;
}

namespace {

/// Iterated to its own solution, the gather needs only a start: a hundredth of a shot per
/// patch, no more than kGatherStartMaxShots shots however many patches there are. Under a time
/// limit the start may be what is shown (the gather given up at its deadline): it keeps its
/// tenth of a shot per patch then.
double iteratedStartShotsPerPatch(const Settings& settings, double shotsPerPatch, size_t patches) {
  if (!(shotsPerPatch > 0)) return shotsPerPatch;
  const double perPatch =
      settings.timeLimit > 0 ? shotsPerPatch : std::min(shotsPerPatch, kIteratedStartShotsPerPatch);
  return std::min(perPatch, double(kGatherStartMaxShots) / double(patches));
}

}  // namespace

GatherPlan planGather(const Settings& settings, const GatherEstimate& estimate, size_t patches, double timeLeft,
                      std::shared_ptr<GatherAhead> ahead) {
  GatherPlan plan;
  plan.shooting = settings.shooting(false);
  if (!settings.finalGather) return plan;
  plan.estimate = estimate;
  plan.leftOut = gatherLeftOut(estimate, workerCount(0), timeLeft, settings.timeLimit);
  plan.on = plan.leftOut.empty();
  if (!plan.on) return plan;
  plan.shooting = settings.shooting(true);
  if (estimate.iterates(GatherOptions{}))
    plan.shooting.shotsPerPatch = iteratedStartShotsPerPatch(settings, plan.shooting.shotsPerPatch, patches);
  plan.ahead = std::move(ahead);
  return plan;
}

}  // namespace rad
