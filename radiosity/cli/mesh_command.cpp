// radiosity mesh SCENE -o OUT.ply: the meshed scene, with per-face surface and patch index.
#include <iostream>
#include <memory>

#include "mesh/mesh_export.h"
#include "mesh/output_file.h"
#include "mesh/patch_mesh.h"
#include "radiosity/settings.h"
#include "radiosity/cli/commands.h"

namespace rad::cli {
namespace {

struct MeshOptions {
  std::string scene, output;
  SolverBlock flags;
};

void runMesh(const MeshOptions& o) {
  checkOutputPath(o.output);
  const MeshedScene meshed = meshWithFlags(loadScene(o.scene), o.flags, false);
  const PatchMesh& mesh = meshed.mesh;
  const Scene& scene = meshed.scene;
  PlyMesh ply = toPly(mesh);
  ply.comments.push_back("radiosity mesh of " + scene.path);
  ply.face.push_back(faceIntColumn(mesh, "patch", &PatchMesh::patch));
  ply.face.push_back(faceIntColumn(mesh, "side", &PatchMesh::side));
  writePly(o.output, ply);
  std::cerr << "radiosity: wrote " << o.output << " (" << mesh.elementCount() << " elements, "
            << mesh.patches.size() << " patches)\n";
}

}  // namespace

Command addMeshCommand(CLI::App& app) {
  auto o = std::make_shared<MeshOptions>();
  CLI::App* sub = app.add_subcommand(
      "mesh", "Mesh the scene into patches and elements and write it as a PLY file (per face: "
              "surface index, patch index, side)");
  addSceneAndOutput(*sub, o->scene, o->output, "Output PLY file");
  addMeshFlags(*sub, o->flags);
  return {sub, [o] { runMesh(*o); }};
}

}  // namespace rad::cli
