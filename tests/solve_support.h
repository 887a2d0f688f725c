#pragma once
// A scene solved the way `radiosity solve` solves it: the shipping pipeline of
// radiosity/solve.h, default settings unless the flags say otherwise.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "mesh/reference_points.h"
#include "radiosity/solve.h"
#include "radiosity/true_error.h"
#include "tests/support.h"

namespace rad::test {

/// A scene meshed and solved as `radiosity solve` does: what it would write, and the solve.
struct Solved {
  MeshedScene meshed;
  std::unique_ptr<RadiositySolve> solve;
  Solution solution;
  /// What Gouraud shading shows at each vertex.
  std::vector<glm::dvec3> shown;
  const ProgressiveSolver& solver() const { return solve->solver(); }
};

/// Solves a scene file as `radiosity solve FILE` with these flags would (the gather's
/// hemicubes rendering beside the rays).
inline std::unique_ptr<Solved> solveLikeCli(const std::string& path, const SolverBlock& flags = {}) {
  auto s = std::make_unique<Solved>();
  Scene scene = loadSceneToSolve(path);
  const Settings settings = resolveSettings(scene, flags);
  s->meshed = meshScene(std::move(scene), settings, {true, nullptr, true});
  s->solve = std::make_unique<RadiositySolve>(s->meshed);
  while (s->solve->step()) {
  }
  s->solution = s->solve->bake();
  s->shown = shownAtVertices(s->meshed, s->solution);
  return s;
}

/// The stored references (radiosity reference) of docs/.
inline const std::string kDocs = kSourceDir + "/docs/";

/// The true error of what a solve shows, against a stored reference; only the points whose
/// tag starts with `tag`.
inline ErrorSummary trueErrorOf(const Solved& s, const std::string& reference, const std::string& tag = "") {
  std::vector<ReferencePoint> points = readReferenceFile(reference).points;
  points.erase(std::remove_if(points.begin(), points.end(),
                              [&](const ReferencePoint& p) { return p.tag.compare(0, tag.size(), tag) != 0; }),
               points.end());
  return TrueError(s.meshed.mesh, s.meshed.scene, points, reference).measure(s.shown);
}

inline double trueError(const Solved& s, const std::string& reference, const std::string& tag = "") {
  return trueErrorOf(s, reference, tag).rms;
}

}  // namespace rad::test
