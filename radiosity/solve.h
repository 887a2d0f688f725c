#pragma once
// The pipeline in one place: scene → patch mesh → direct light at the vertices and adaptive
// refinement → progressive solve → the baked result. Every command, every test that solves
// "like the CLI" and every benchmark goes through here.
//
//   MeshedScene scene = meshScene(loadSceneToSolve(path), settings);   // meshing, decided once
//   Solution solution = solveRadiosity(scene);                          // one call
// or, to watch it converge,
//   RadiositySolve solve(scene);
//   while (solve.step()) { ... solve.solver().unshotFraction() ... }
//   Solution solution = solve.bake();
#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/facing.h"
#include "mesh/patch_mesh.h"
#include "mesh/scene/scene.h"
#include "radiosity/adaptive.h"
#include "radiosity/gather/final_gather.h"
#include "radiosity/gather_plan.h"
#include "radiosity/light/direct_light.h"
#include "radiosity/settings.h"
#include "radiosity/shooting/progressive_solver.h"
#include "radiosity/vertex_radiosity.h"

namespace rad {

/// Loads a scene file for solving: loadScene, then an error unless some surface emits.
Scene loadSceneToSolve(const std::string& path);

/// A scene meshed by its settings, ready to solve.
struct MeshedScene {
  Scene scene;
  Settings settings;
  PatchMesh mesh;
  /// Direct light at the vertices by rays: null when settings.vertexDirect is off or the
  /// scene's emitters are too many for rays (lightByRays, decided before meshing).
  std::unique_ptr<DirectLight> direct;
  AdaptiveStats adaptive;            ///< what adaptive refinement did
  std::shared_ptr<const PatchMesh> base;  ///< the mesh before refinement (null if nothing was refined)
  /// The final gather, decided once the rays are cast: whether it runs (settings.finalGather,
  /// unless its budget says why not, in a warning), what it costs, and what the progressive
  /// solve shoots with.
  GatherPlan gather;
  /// When meshing began: settings.timeLimit counts from here, the solve and its gather get
  /// what meshing left of it.
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  /// Mesh-file surfaces turned to face the lit space before meshing (settings.fixFacing).
  FacingRepair facing;
  /// Per vertex (with the gather on and refinement done): whether, added by refinement, it
  /// gathers through its own hemicube, another surface lying nearer to it than its base element
  /// is long (nearSurfaces); empty: none does.
  std::vector<char> ownHemicube;
};

/// How many vertices gather through hemicubes of their own (MeshedScene::ownHemicube).
inline long ownHemicubes(const MeshedScene& s) {
  return long(std::count(s.ownHemicube.begin(), s.ownHemicube.end(), char(1)));
}

struct MeshingOptions {
  /// An error when no emitting element is left once contacts are cut, before any ray is cast
  /// (a solve needs light; `radiosity info` and `mesh` do not).
  bool requireEmitter = false;
  /// Called with each of the mesher's warnings (repairs, approximations) once, as they arise.
  std::function<void(const std::string&)> warn;
  /// A solve follows: the final gather's hemicubes start rendering as soon as the mesh they
  /// draw is known, on threads of their own beside the rays and the shots (GatherAhead), when
  /// the gather is on and its rows fit its memory. The result is the same, bit for bit.
  bool gatherAhead = false;
};

/// Meshes the scene by its settings, deciding everything before any solving: the uniform mesh
/// (contact lines graded beforehand when no refinement will grade them), the direct light at
/// its vertices by rays, and adaptive refinement where that light changes visibly.
MeshedScene meshScene(Scene scene, const Settings& settings, const MeshingOptions& options = {});

/// The solver options of the settings shooting as `shooting` says, for a mesh of `patches`
/// patches (which Shooting::shotsPerPatch counts).
SolverOptions solverOptions(const Settings& settings, const Shooting& shooting, size_t patches);
/// The same for a meshed scene: its settings, shooting as its gather's plan says.
SolverOptions solverOptions(const MeshedScene& scene);
/// The seconds of settings.timeLimit the scene has left (0: no limit; else at least
/// kNoTimeLeft, once spent).
double timeLeft(const MeshedScene& scene);
/// Hemicubes at the settings' resolutions and seed (workers 0: one per hardware thread).
std::unique_ptr<HemicubeFactors> hemicubeFactors(const MeshedScene& scene, int workers = 0);

/// A solution as the result file holds it (DESIGN.md, "Result mesh").
struct Solution {
  std::vector<glm::dvec3> B;   ///< element radiosity, negative channels (overshoot) set to 0
  glm::dvec3 ambient{0.0};     ///< ambient term shown while unconverged (0 once converged)
  int clamped = 0;             ///< elements that had a negative channel
  bool converged = false;      ///< stopped by the tolerance
  /// The direct light the vertices show (none without rays): the display equation's D.
  std::optional<VertexDirect> direct;
  /// After the final gather: what each vertex shows (B then holds each element's mean of its
  /// corners, the ambient term is 0: the gather solves the vertex system to convergence).
  std::optional<std::vector<glm::dvec3>> gathered;
  GatherStats gather;
};

/// What Gouraud shading shows at each vertex of the scene's mesh (the display equation,
/// radiosity/vertex_radiosity.h).
std::vector<glm::dvec3> shownAtVertices(const MeshedScene& scene, const Solution& solution);

/// A solve in progress over a meshed scene, which must outlive it: its hemicubes and the
/// progressive solver.
class RadiositySolve {
 public:
  /// workers: hemicubes rendering at once (0: one per hardware thread).
  explicit RadiositySolve(const MeshedScene& scene, int workers = 0);
  RadiositySolve(const MeshedScene& scene, const SolverOptions& options, int workers = 0);

  /// One shot; false once a stop condition holds.
  bool step() { return solver_.step(); }
  const ProgressiveSolver& solver() const { return solver_; }
  /// The current solution, baked (negative channels clamped, the ambient term while
  /// unconverged, the vertices' direct light), and gathered at the vertices if the settings
  /// say so and `gather` allows.
  Solution bake(bool gather = true) const;

 private:
  /// The final gather over a baked solution.
  void gatherAtVertices(Solution& b) const;

  const MeshedScene& scene_;
  int workers_;
  std::unique_ptr<HemicubeFactors> factors_;
  ProgressiveSolver solver_;
};

/// One call: solves to the settings' stop condition and bakes.
Solution solveRadiosity(const MeshedScene& scene);

/// The exposure the result is shown at: the settings' or autoExposure's.
double exposureOf(const MeshedScene& scene, const Solution& solution);
/// The scene's camera, or the default one.
Camera cameraOf(const Scene& scene);

/// Writes the result mesh of a solution (atomic: temporary file, then rename).
void writeSolution(const std::string& path, const MeshedScene& scene, const Solution& solution);

}  // namespace rad
