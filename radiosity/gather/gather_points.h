#pragma once
// Where the final gather renders its hemicubes. Adaptive refinement adds vertices where the
// direct light changes (a penumbra's edge), which the rays compute at every vertex. The
// vertices of the mesh as built before refinement gather; a vertex refinement added takes the
// light gathered at the corners of its base element, interpolated linearly at its position,
// unless another surface is nearer to it than that element is long (a tread's side beside the
// wall it enters, the floor under a sofa's edge, a ceiling round a lamp): there the indirect
// light changes faster than the corners follow, and the vertex gathers through its own hemicube.
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"

namespace rad {

class DirectLight;

struct GatherPoints {
  std::vector<bool> at;  ///< per vertex: gathers through its own hemicube
  /// Per vertex: the gathering vertices its gathered light is interpolated from, with their
  /// weights (a gathering vertex: itself, weight 1; a black one: none).
  std::vector<std::vector<std::pair<int, double>>> from;
  /// Per gathering vertex: the vertex of the drawn mesh (the base, or the mesh itself) at its
  /// place, whose hemicube it gathers through; -1 for the others (and for a gathering vertex
  /// that is not one of the drawn mesh's: it renders its own).
  std::vector<int> drawn;

  /// Values at every vertex from values at the gathering ones.
  std::vector<glm::dvec3> spread(const std::vector<glm::dvec3>& atPoints) const;
  int count() const;
};

/// Per vertex of the drawn mesh, the gathering vertices (of the drawn mesh) its gathered light
/// is interpolated from (GatherCache::from).
using DrawnInterpolation = std::vector<std::vector<std::pair<int, double>>>;

/// The gathering vertices of `mesh`, whose reflectance per vertex is `rho` (black vertices
/// gather nothing): with `base` (the mesh before refinement) its corners and the vertices
/// `ownHemicube` marks (if given), else every vertex. With `drawn` (per vertex of the base, or
/// of the mesh without one), the vertices it does not have gather take its interpolation
/// instead, and so do the vertices refinement added inside their elements.
GatherPoints gatherPoints(const PatchMesh& mesh, const PatchMesh* base, const std::vector<glm::dvec3>& rho,
                          const std::vector<char>* ownHemicube = nullptr, const DrawnInterpolation* drawn = nullptr);

/// Per vertex of `mesh`, refined from `base`: whether it gathers through its own hemicube,
/// another surface lying nearer to it than its base element's longest edge (any of the short
/// rays DirectLight::surfacesWithin casts meets one). The corners of `base` are not asked.
std::vector<char> nearSurfaces(const PatchMesh& mesh, const PatchMesh& base, const DirectLight& light);

}  // namespace rad
