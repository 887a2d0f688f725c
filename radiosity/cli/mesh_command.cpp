// radiosity mesh SCENE -o OUT.ply: the meshed scene, with per-face surface and patch index.
#include <iostream>
#include <memory>

#include "mesh/base/output_file.h"
#include "mesh/patch_mesh.h"
#include "mesh/results/mesh_export.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/cli/commands.h"
#include "radiosity/settings.h"

namespace rad::cli {
namespace {

struct MeshOptions {
  std::string scene, output;
  SolverBlock flags;
};

/// The mesh as PLY, each face with its surface, patch and side.
PlyMesh meshPly(const PatchMesh& mesh, const Scene& scene) {
  PlyMesh ply = toPly(mesh);
  ply.comments.push_back("radiosity mesh of " + scene.path);
  ply.face.push_back(faceIntColumn(mesh, "patch", &PatchMesh::patch));
  ply.face.push_back(faceIntColumn(mesh, "side", &PatchMesh::side));
  return ply;
}

void runMesh(const MeshOptions& o) {
  checkOutputPath(o.output);
  const MeshedScene meshed = meshWithFlags(loadScene(o.scene), o.flags, false);
  const PatchMesh& mesh = meshed.mesh;
  writePly(o.output, meshPly(mesh, meshed.scene));
  std::cerr << "radiosity: wrote " << o.output << " (" << mesh.elementCount() << " elements, "
            << mesh.patches.size() << " patches)\n";
}

}  // namespace

Command addMeshCommand(CLI::App& app) {
  Subcommand<MeshOptions> c(app, "mesh",
                            "Mesh the scene into patches and elements and write it as a PLY file (per face: "
                            "surface index, patch index, side)");
  addSceneAndOutput(*c.app, c.o->scene, c.o->output, "Output PLY file");
  addMeshFlags(*c.app, c.o->flags);
  return c.runs(runMesh);
}

}  // namespace rad::cli
