#pragma once
// Baking a solution into the result mesh (DESIGN.md, "Result mesh"): vertex radiosities,
// display colours and the exposure rule.
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"
#include "mesh/scene.h"

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

/// The share of non-emitting area at or below the exposure's reference luminance.
constexpr double kExposurePercentile = 0.95;
/// The display value (linear, before sRGB) the reference luminance maps to.
constexpr double kExposureTarget = 0.8;

/// Automatic exposure K: the area-weighted 95th percentile of element luminance over the
/// non-emitting elements maps to 0.8 (linear), so emitters saturate and walls keep detail.
/// 1 when nothing non-emitting is lit.
double autoExposure(const PatchMesh& mesh, const std::vector<glm::dvec3>& B);

/// A camera for scenes without one: looking along +z at the centre of the bounding box from
/// far enough to see all of it.
Camera defaultCamera(const Scene& scene);

/// Writes the result mesh: per vertex position, normal, display colour sRGB(clamp(K·(B + ρ·a)))
/// and linear radiosity B; per face the surface index and the element's own B. `ambient` (a) is
/// added to the display colour only (zero once converged). With `direct`, vertex radiosities
/// take their direct light from it. Atomic: temporary file, then rename.
void writeResult(const std::string& path, const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                 const glm::dvec3& ambient, double exposure, const Camera& camera,
                 const VertexDirect* direct = nullptr);

/// The element radiosities of an earlier result of the same scene and mesh settings, for
/// comparison. Throws InputError when the file is not such a result (element count, geometry
/// or the face radiosity properties differ).
std::vector<glm::dvec3> readResultRadiosity(const std::string& path, const PatchMesh& mesh,
                                            double sceneSize);

}  // namespace rad
