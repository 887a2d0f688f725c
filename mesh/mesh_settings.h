#pragma once
// The meshing part of the run settings, resolved where every part can reach it: the solver
// (radiosity/settings.h adds the rest) and the viewer's local-lighting mode mesh a scene alike.
#include "mesh/patch_mesh.h"
#include "mesh/scene.h"

namespace rad {

/// Default element edge: the scene diagonal divided by this.
constexpr double kDefaultElementsPerDiagonal = 25;
/// Default patch edge: this many element edges.
constexpr double kDefaultPatchToElement = 3;

/// Contact lines are graded by the mesher unless adaptive refinement will grade them.
inline double contactGrading(bool adaptive) { return adaptive ? 1.0 : kDefaultContactGrading; }

/// `flags` over `scene.solver` over the defaults, for the meshing settings: element and patch
/// edges, contact cutting, and the contact grading adaptive refinement implies.
MeshSettings resolveMeshSettings(const Scene& scene, const SolverBlock& flags);

}  // namespace rad
