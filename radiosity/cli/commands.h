#pragma once
// The subcommands of the `radiosity` command line. Each registers its options on the app
// and returns the function that runs it; errors are thrown (InputError) and reported by main.
#include <functional>
#include <memory>

#include <CLI/CLI.hpp>

#include "mesh/patch_mesh.h"
#include "mesh/scene.h"
#include "mesh/settings.h"
#include "radiosity/adaptive.h"
#include "radiosity/direct_light.h"
#include "radiosity/progressive_solver.h"
#include "radiosity/result.h"
#include "radiosity/true_error.h"

namespace rad::cli {

/// A subcommand and the function that runs it once its options are parsed.
struct Command {
  CLI::App* app;
  std::function<void()> run;
};

/// Flags shared by every command that meshes: one name each, as in the scene's solver block.
void addMeshFlags(CLI::App& app, SolverBlock& flags);
/// --hemicube and --seed, shared by every command that computes form factors.
void addSolverFlags(CLI::App& app, SolverBlock& flags);

Command addInfoCommand(CLI::App& app);
Command addMeshCommand(CLI::App& app);
Command addFormFactorsCommand(CLI::App& app);
Command addSolveCommand(CLI::App& app);
Command addConvergenceCommand(CLI::App& app);
Command addReferenceCommand(CLI::App& app);

/// A scene loaded, checked to have an emitter, its settings resolved and meshed (warnings
/// printed): what every solving command starts from.
struct SolvableScene {
  Scene scene;
  Settings settings;
  PatchMesh mesh;
  /// Direct light at the vertices by rays (null when the scene's emitters are too many for it,
  /// or settings.vertexDirect is off), and what adaptive refinement did with it.
  std::unique_ptr<DirectLight> direct;
  AdaptiveStats adaptive;
  std::unique_ptr<PatchMesh> base;  ///< the mesh before refinement, if refined
};
SolvableScene loadSolvable(const std::string& path, const SolverBlock& flags);
/// Meshes a loaded scene by its settings: the uniform mesh, then adaptive refinement; the
/// mesher's warnings printed. needsEmitter: an error when contacts cut every emitter away.
SolvableScene meshScene(Scene scene, const SolverBlock& flags, bool needsEmitter);

/// The solver options the settings give.
SolverOptions solverOptions(const Settings& settings);
/// Hemicubes at the settings' resolutions and seed (workers 0: one per hardware thread).
std::unique_ptr<HemicubeFactors> hemicubeFactors(const SolvableScene& s, int workers);

/// A solution as baked: B without negative channels, and the ambient term while unconverged.
struct Baked {
  std::vector<glm::dvec3> B;
  glm::dvec3 ambient{0.0};
  int clamped = 0;
};

/// The solver's current solution as the result file bakes it.
Baked bake(const ProgressiveSolver& solver, bool directAtVertices);
/// The direct light the vertices show (null without rays).
std::unique_ptr<VertexDirect> vertexDirect(const ProgressiveSolver& solver, const SolvableScene& s);
/// The true error of what a viewer would show of the solver's current solution.
ErrorSummary trueErrorNow(const ProgressiveSolver& solver, const SolvableScene& s, const TrueError& truth);

/// Prints the loader's and the mesher's warnings on stderr.
void printWarnings(const std::vector<std::string>& warnings);

}  // namespace rad::cli
