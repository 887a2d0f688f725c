#pragma once
// A scene solved the way `radiosity solve` solves it: the shipping pipeline of
// radiosity/solve.h, default settings unless the flags say otherwise.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/base/color.h"
#include "mesh/results/reference_points.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/shooting/progressive_solver.h"
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

/// The stored references (radiosity reference) of the shipped scenes.
inline const std::string kReferences = kSourceDir + "/tests/data/references/";

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

/// The unit cube (`scenes/cube.json`: closed, only the ceiling emits), every material's
/// reflectance rho.
inline Scene greyCube(double rho) {
  Scene scene = loadScene(kScenes + "cube.json");
  for (auto& m : scene.materials) m.reflectance = glm::dvec3(rho);
  return scene;
}

/// In a closed box of uniform reflectance rho nothing escapes, so after any number of shots the
/// power held and the power still unshot add up to the generalised furnace's (oracles.md §4):
/// Σ A·B + ρ/(1 − ρ)·Σ A·ΔB = Σ A·E / (1 − ρ), and the ledger closes, all to 1e-9.
inline void expectClosedBoxFurnace(const PatchMesh& mesh, const ProgressiveSolver& solver, double rho) {
  const EnergyLedger& l = solver.ledger();
  EXPECT_LE(luminance(l.escaped), 1e-9 * luminance(l.emitted));
  EXPECT_LE(l.residual(), 1e-9);
  double held = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) held += mesh.area(e) * luminance(solver.radiosity()[e]);
  EXPECT_NEAR((held + rho / (1 - rho) * luminance(l.unshot)) / (luminance(l.emitted) / (1 - rho)), 1.0, 1e-9);
}

}  // namespace rad::test
