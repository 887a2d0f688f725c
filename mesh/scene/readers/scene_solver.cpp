// The scene file's "solver" section: defaults that command-line flags override.
#include <cmath>
#include <optional>

#include "mesh/scene/readers/scene_sections.h"

namespace rad::scene_file {
namespace {

/// slot = the number at `key` in [lo, hi] (said as `range`), if the key is there.
template <class T>
void optionalNumber(const Node& n, const char* key, double lo, double hi, const char* range,
                    std::optional<T>& slot) {
  if (n.has(key)) slot = n[key].number(lo, hi, range);
}

/// slot = the whole number at `key` in [lo, hi] (said as `range`), if the key is there.
template <class T>
void optionalWhole(const Node& n, const char* key, double lo, double hi, const char* range,
                   std::optional<T>& slot) {
  if (n.has(key)) slot = T(n[key].wholeNumber(lo, hi, range));
}

/// slot = the flag at `key`, if the key is there.
void optionalBool(const Node& n, const char* key, std::optional<bool>& slot) {
  if (n.has(key)) slot = n[key].boolean();
}

/// slot = the hemicube resolution at `key` (an even whole number), if the key is there.
void optionalResolution(const Node& n, const char* key, std::optional<int>& slot) {
  if (!n.has(key)) return;
  Node r = n[key];
  double x = r.number(2, 8192, "[2, 8192]");
  if (x != std::floor(x) || int(x) % 2) r.fail("an even whole number");
  slot = int(x);
}

/// slot = the quality named at `key`, if the key is there.
void optionalQuality(const Node& n, const char* key, std::optional<Quality>& slot) {
  if (!n.has(key)) return;
  const Node q = n[key];
  const std::string name = q.string();
  if (name == "draft")
    slot = Quality::Draft;
  else if (name == "default")
    slot = Quality::Default;
  else if (name == "final")
    slot = Quality::Final;
  else
    q.fail("\"draft\", \"default\" or \"final\"");
}

/// Lengths, limits and switches, in the order they are checked.
void readSolverNumbers(const Node& n, SolverBlock& b) {
  optionalNumber(n, "max_element_edge", 1e-300, HUGE_VAL, "(0, inf)", b.maxElementEdge);
  optionalNumber(n, "max_patch_edge", 1e-300, HUGE_VAL, "(0, inf)", b.maxPatchEdge);
  optionalNumber(n, "tolerance", 1e-300, 1, "(0, 1]", b.tolerance);
  optionalNumber(n, "time_limit", 1e-300, HUGE_VAL, "(0, inf)", b.timeLimit);
  optionalNumber(n, "overshoot", 1, 2, "[1, 2]", b.overshoot);
  optionalNumber(n, "exposure", 1e-300, HUGE_VAL, "(0, inf)", b.exposure);
  optionalBool(n, "cut_contacts", b.cutContacts);
  optionalBool(n, "fix_facing", b.fixFacing);
  optionalBool(n, "adaptive", b.adaptive);
  optionalBool(n, "vertex_direct", b.vertexDirect);
  optionalBool(n, "final_gather", b.finalGather);
  optionalBool(n, "cluster_shooters", b.clusterShooters);
  optionalBool(n, "resolution_follows_power", b.resolutionFollowsPower);
  optionalNumber(n, "min_element_edge", 1e-300, HUGE_VAL, "(0, inf)", b.minElementEdge);
  optionalNumber(n, "contrast", 1e-6, 1, "[1e-6, 1]", b.contrast);
  optionalNumber(n, "proximity_samples", 0, 65536, "[0, 65536]", b.proximitySamples);
  optionalNumber(n, "factor_cache_mb", 0, 1e9, "[0, 1e9]", b.factorCacheMb);
  optionalNumber(n, "gather_accuracy", 0, 1, "[0, 1]", b.gatherAccuracy);
}

/// Counts, resolutions and the seed, in the order they are checked.
void readSolverCounts(const Node& n, SolverBlock& b) {
  optionalWhole(n, "emitter_samples", 1, 65536, "[1, 65536]", b.emitterSamples);
  optionalWhole(n, "shooter_samples", 1, 65536, "[1, 65536]", b.shooterSamples);
  optionalWhole(n, "max_elements", 1, 1e12, "[1, 1e12]", b.maxElements);
  optionalWhole(n, "max_shots", 1, 1e15, "[1, 1e15]", b.maxShots);
  optionalResolution(n, "hemicube_resolution", b.hemicubeResolution);
  optionalResolution(n, "emitter_hemicube_resolution", b.emitterHemicubeResolution);
  optionalResolution(n, "gather_resolution", b.gatherResolution);
  optionalWhole(n, "seed", 0, 4294967295.0, "[0, 2^32)", b.seed);
}

}  // namespace

void readSolver(const Node& n, SolverBlock& b) {
  n.expectObject({"quality", "max_element_edge", "max_patch_edge", "hemicube_resolution",
                  "emitter_hemicube_resolution", "tolerance",
                  "seed", "max_shots", "time_limit", "overshoot", "exposure", "emitter_samples",
                  "shooter_samples", "proximity_samples", "factor_cache_mb", "cut_contacts", "fix_facing",
                  "adaptive", "min_element_edge", "contrast", "vertex_direct", "max_elements",
                  "final_gather", "gather_resolution", "gather_accuracy", "cluster_shooters",
                  "resolution_follows_power"});
  optionalQuality(n, "quality", b.quality);
  readSolverNumbers(n, b);
  readSolverCounts(n, b);
}

}  // namespace rad::scene_file
