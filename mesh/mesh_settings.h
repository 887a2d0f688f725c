#pragma once
// The meshing part of the run settings, resolved where every part can reach it: the solver
// (radiosity/settings.h adds the rest) and the viewer's local-lighting mode mesh a scene alike.
#include "mesh/patch_mesh.h"
#include "mesh/scene/scene.h"

namespace rad {

/// Default element edge: the scene diagonal divided by this.
constexpr double kDefaultElementsPerDiagonal = 25;
/// A draft's elements are this many times as long as the scene's (its own or the default), a
/// final solve's this many times shorter, unless the flag sets the edge (docs/method/true-error.md,
/// "Quality").
constexpr double kQualityElementRatio = 1.6;

/// The quality the flags or else the scene ask for (default: Quality::Default).
inline Quality qualityOf(const Scene& scene, const SolverBlock& flags) {
  return flags.quality.value_or(scene.solver.quality.value_or(Quality::Default));
}

/// What a quality scales the scene's element edge by.
inline double elementScale(Quality q) {
  return q == Quality::Draft ? kQualityElementRatio : q == Quality::Final ? 1 / kQualityElementRatio : 1.0;
}
/// Default patch edge: this many element edges.
constexpr double kDefaultPatchToElement = 3;

/// Contact lines are graded by the mesher unless adaptive refinement will grade them, and
/// always for the final gather: refinement follows the direct light, but the indirect light
/// changes fastest at a contact too (the block beside a floor point hides half its sky), and
/// Gouraud shading needs small elements there to show it (measured: within 50 mm of the
/// Cornell box's blocks, 16.9 % RMS ungraded, 6.5 % at 4×, 3.9 % at 8×).
inline double contactGrading(bool adaptive, bool finalGather) {
  return adaptive && !finalGather ? 1.0 : kDefaultContactGrading;
}

/// `flags` over `scene.solver` over the defaults, for the meshing settings: element and patch
/// edges, contact cutting, and the contact grading adaptive refinement implies.
MeshSettings resolveMeshSettings(const Scene& scene, const SolverBlock& flags);

}  // namespace rad
