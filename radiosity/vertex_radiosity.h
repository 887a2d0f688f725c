#pragma once
// The display equation: what a viewer shows at each vertex of the result mesh.
//
//   shown(v) = D(v) + I(v) + ρ(v)·a
//
// D(v), the direct light: the emitters' light at the vertex itself, computed there by rays
//   (DirectLight; VertexDirect::vertex). Without rays it is not split off: I(v) then carries
//   all of B.
// I(v), the rest (indirect light, and the emitter's own emission): the element radiosities
//   minus the part the emitters delivered to them in the first bounce (VertexDirect::element),
//   reconstructed at the vertices (area-weighted means, linear fits on borders), at the base
//   mesh's resolution when the mesh was refined for the direct light (VertexDirect::base).
// a, the ambient term of an unconverged solve (Cohen et al. 1988), zero once converged; ρ(v)
//   the reflectance of the vertex's surface.
// Every consumer (the result file, the true error, the tests) takes the vertex values from here,
// unless the final gather ran (radiosity/gather/final_gather.h, the default): it replaces I(v) by the
// light gathered at the vertex itself, the vertex system solved, so a = 0:
//   shown(v) = E(v) + D(v) + ρ(v)·Σⱼ F_vj·(reflected light of element j).
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"

namespace rad {

/// Vertex radiosities for Gouraud display: the area-weighted mean of the elements around each
/// vertex, or, on a surface's border, the value at the vertex of a linear fit to the elements
/// around it and their neighbours (vertices belong to one side of one surface, so creases and
/// material edges stay sharp).
std::vector<glm::dvec3> vertexRadiosity(const PatchMesh& mesh, const std::vector<glm::dvec3>& B);

/// Direct light known at the vertices (computed there by rays) and the part of each element's
/// radiosity it replaces (what the solver's emitters delivered to it). With `base`, the mesh
/// as built before adaptive refinement, the rest (the indirect light) is reconstructed at the
/// base mesh's resolution: refinement follows the direct light, and below the base size the
/// hemicubes' indirect light on small elements is mostly aliasing (a few pixels each).
struct VertexDirect {
  std::vector<glm::dvec3> element, vertex;
  const PatchMesh* base = nullptr;
};

/// As above, with the direct light taken from the vertices: each element's direct part is
/// taken out before the reconstruction, and the vertex's own direct light added after. With
/// direct->base, the rest is averaged over each base element, reconstructed at the base
/// mesh's vertices, and interpolated linearly inside each base element (substructuring).
std::vector<glm::dvec3> vertexRadiosity(const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                                        const VertexDirect* direct);

/// What Gouraud shading shows at each vertex: the vertex radiosity of B + ρ·ambient (the
/// ambient term of an unconverged solve; zero once converged), with `direct` as above.
std::vector<glm::dvec3> shownVertexRadiosity(const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                                             const glm::dvec3& ambient, const VertexDirect* direct);

/// The value Gouraud shading shows at point x: the vertex values of the element among
/// `elements` that contains x (within its plane's tolerance of 1e-6 of its size), interpolated
/// barycentrically; nullopt when none does.
std::optional<glm::dvec3> gouraudAt(const PatchMesh& mesh, const std::vector<int>& elements,
                                    const std::vector<glm::dvec3>& vertexValue, const glm::dvec3& x);

}  // namespace rad
