#pragma once
// Internal to the scene loader: the readers of the scene file's sections, each validating
// what it reads (DESIGN.md, "Scene file").
#include <string>

#include "mesh/scene/readers/mesh_file.h"
#include "mesh/scene/readers/scene_json.h"
#include "mesh/scene/scene.h"

namespace rad::scene_file {

/// "materials": named materials, appended to scene.materials in file order.
void readMaterials(const Node& n, Scene& scene);

/// The index of the material a "material" key names.
int materialIndex(const Node& n, const Scene& scene);

/// A material from a mesh file's MTL group (Kd reflectance, Ke radiance), appended to
/// scene.materials; `s` is the surface that names the mesh file. Returns its index.
int addMtlMaterial(const Node& s, const MeshFileGroup& group, Scene& scene);

/// "surfaces": polygons and mesh files (relative to baseDir), appended to scene.surfaces.
void readSurfaces(const Node& n, const std::string& baseDir, Scene& scene);

/// Every point within the coordinates double precision meshes well, and the scene not too
/// small.
void checkScale(const Scene& scene);

/// The display-only sections: "camera", "light_model", "lights", "fog".
Camera readCamera(const Node& n);
void readLightModel(const Node& n, LightModel& model);
void readLights(const Node& n, std::vector<Light>& lights);
Fog readFog(const Node& n);

/// "solver": the defaults that command-line flags override.
void readSolver(const Node& n, SolverBlock& b);

}  // namespace rad::scene_file
