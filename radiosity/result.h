#pragma once
// Baking a solution into the result mesh (DESIGN.md, "Result mesh"): vertex radiosities,
// display colours and the exposure rule.
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"
#include "mesh/scene/camera.h"
#include "mesh/scene/scene.h"
#include "radiosity/vertex_radiosity.h"

namespace rad {

/// The share of non-emitting area at or below the exposure's reference luminance.
constexpr double kExposurePercentile = 0.95;
/// The display value (linear, before sRGB) the reference luminance maps to.
constexpr double kExposureTarget = 0.8;

/// Automatic exposure K: the area-weighted 95th percentile of element luminance over the
/// non-emitting elements maps to 0.8 (linear), so emitters saturate and walls keep detail.
/// 1 when nothing non-emitting is lit.
double autoExposure(const PatchMesh& mesh, const std::vector<glm::dvec3>& B);

/// Writes the result file (mesh/results/result_file.h): per vertex (every vertex a face uses; one
/// that no face uses has no normal and no light, and is left out) position, normal, display colour
/// sRGB(clamp(K·(B + ρ·a))) and linear radiosity B; per face the surface index and the element's
/// own B. `ambient` (a) is added to the display colour only (zero once converged). With `direct`,
/// vertex radiosities take their direct light from it. Atomic: temporary file, then rename.
void writeResult(const std::string& path, const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                 const glm::dvec3& ambient, double exposure, const Camera& camera,
                 const VertexDirect* direct = nullptr);

/// Writes the result file with the vertex radiosities given (the final gather's) and the
/// elements' `B`; the display colours from the vertex values.
void writeVertexResult(const std::string& path, const PatchMesh& mesh, const std::vector<glm::dvec3>& vertexB,
                       const std::vector<glm::dvec3>& B, double exposure, const Camera& camera);

/// The element radiosities of an earlier result of the same scene and mesh settings, for
/// comparison. Throws InputError when the file is not such a result (element count, geometry
/// or the face radiosity properties differ).
std::vector<glm::dvec3> readResultRadiosity(const std::string& path, const PatchMesh& mesh,
                                            double sceneSize);

}  // namespace rad
