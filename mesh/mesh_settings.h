#pragma once
// The meshing part of the run settings, resolved where every part can reach it: the solver
// (radiosity/settings.h adds the rest) and the viewer's local-lighting mode mesh a scene alike.
#include "mesh/patch_mesh.h"
#include "mesh/scene/scene.h"

namespace rad {

/// Default element edge: the scene diagonal divided by this.
constexpr double kDefaultElementsPerDiagonal = 25;
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
