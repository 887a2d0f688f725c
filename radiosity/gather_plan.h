#pragma once
// The final gather, decided once (radiosity/solve.h): after the mesh it draws is built and the
// rays are cast, whether it runs and why not, what it costs, and what the progressive solve
// shoots with: the gather's cheap start, or the full shooting of a solve that is the answer.
#include <chrono>
#include <memory>
#include <string>

#include "radiosity/gather/final_gather.h"
#include "radiosity/settings.h"

namespace rad {

/// What timeLeft says once the time limit is spent (positive: 0 means no limit).
constexpr double kNoTimeLeft = 1e-9;
/// The gather may take at most this share of the time a time limit leaves after meshing.
constexpr double kGatherShareOfTimeLeft = 0.5;

struct GatherPlan {
  bool on = false;  ///< the solution is gathered at the vertices
  /// Why the gather the settings ask for is left out, as the warning says it; empty when it
  /// runs or was not asked for.
  std::string leftOut;
  /// What it costs: estimateGather over the mesh before refinement, scaled to the vertices
  /// refinement added that gather through their own hemicubes (zeros when not asked for).
  GatherEstimate estimate{};
  /// What the progressive solve shoots with: the settings' gather start when the gather runs
  /// (a hundredth of a shot per patch when it iterates, Settings::shooting), else the
  /// settings' own shooting.
  Shooting shooting;
  /// The gather's hemicubes, rendering since the mesh they draw was known, or null: then the
  /// gather renders them itself.
  std::shared_ptr<GatherAhead> ahead;
};

/// Why the final gather is left out, as the warning says it, or empty: meshing spent the time
/// limit (`timeLimit`), or it would take more than kMaxGatherSeconds on one core, or more than
/// kGatherShareOfTimeLeft of what the limit leaves (`timeLeft`; 0: no limit) on `workers`.
std::string gatherLeftOut(const GatherEstimate& estimate, int workers, double timeLeft, double timeLimit);

/// The gather's options by the settings, its deadline the time limit counted from `started`.
GatherOptions gatherOptions(const Settings& settings, std::chrono::steady_clock::time_point started);

/// The plan for a mesh of `patches` patches with `timeLeft` seconds of the time limit left (0:
/// no limit). `ahead` (rendering already, or null) is kept only if the gather runs.
GatherPlan planGather(const Settings& settings, const GatherEstimate& estimate, size_t patches, double timeLeft,
                      std::shared_ptr<GatherAhead> ahead);

}  // namespace rad
