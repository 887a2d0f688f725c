#pragma once
// A scene solved the way `radiosity solve` solves it: the shipping pipeline of
// radiosity/solve.h, default settings unless the flags say otherwise.
#include <memory>
#include <string>
#include <vector>

#include "radiosity/solve.h"
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

}  // namespace rad::test
