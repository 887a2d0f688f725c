#pragma once
// The JSON report of `radiosity solve` (DESIGN.md, "Report"): settings, counts, what the scene
// did not need, the energy ledger, the true error and the history.
#include <string>

#include <nlohmann/json.hpp>

#include "mesh/base/stage_times.h"
#include "radiosity/solve.h"
#include "radiosity/true_error.h"

namespace rad::cli {

using Json = nlohmann::ordered_json;

Json rgb(const glm::dvec3& c);
const char* stopName(ProgressiveSolver::Stop s);

/// The report's "error" block: the definition, the reference and the summary.
Json errorBlock(const ErrorSummary& e, const TrueError& truth, const std::string& file);
/// Every reference point with what is shown there.
Json pointsTable(const TrueError& truth, const std::vector<glm::dvec3>& shown);

/// The time of each stage of the run and the peak memory once it was done, as
/// [{"name", "seconds", "peak_mib"}, ...].
Json stagesTable(const StageTimes& stages);

/// Everything the report says of a finished solve, but the history and the error.
Json solveReport(const MeshedScene& scene, const RadiositySolve& solve, const Solution& solution);

}  // namespace rad::cli
