#pragma once
// The subcommands of the `radiosity` command line. Each registers its options on the app
// and returns the function that runs it; errors are thrown (InputError) and reported by main.
#include <functional>
#include <memory>

#include <CLI/CLI.hpp>

#include "mesh/base/stage_times.h"
#include "mesh/scene/scene.h"
#include "radiosity/settings.h"
#include "radiosity/solve.h"
#include "radiosity/true_error.h"

namespace rad::cli {

/// A subcommand and the function that runs it once its options are parsed.
struct Command {
  CLI::App* app;
  std::function<void()> run;
};

/// A subcommand being registered: its CLI app and its options, which the flags write and the
/// run reads (shared with the callback, so they outlive the parse).
template <class Options>
struct Subcommand {
  std::shared_ptr<Options> o = std::make_shared<Options>();
  CLI::App* app;

  Subcommand(CLI::App& parent, const std::string& name, const std::string& description)
      : app(parent.add_subcommand(name, description)) {}
  /// The command, running `run` with the parsed options.
  Command runs(void (*run)(const Options&)) const {
    return {app, [o = o, run] { run(*o); }};
  }
};

/// The required scene file argument.
void addScene(CLI::App& app, std::string& scene);
/// The scene file argument and the required -o/--output file.
void addSceneAndOutput(CLI::App& app, std::string& scene, std::string& output, const std::string& outputHelp);
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

/// The scene meshed by the flags over its solver block (radiosity/solve.h), the loader's
/// warnings printed first and the mesher's as they arise.
MeshedScene meshWithFlags(Scene scene, const SolverBlock& flags, bool requireEmitter);

/// The scene file at `path` read by `load` (loadScene, loadSceneToSolve) and meshed as by
/// meshWithFlags, the time of each stage added to `stages`: "loading", the mesher's own
/// (MeshStats::stages) and "direct light and refinement" (the rest of meshScene).
MeshedScene loadAndMesh(const std::string& path, Scene (*load)(const std::string&), const SolverBlock& flags,
                        bool requireEmitter, StageTimes& stages);

/// The true error of what a viewer would show of the solve's current solution: as the
/// progressive solver has it, or after the final gather (`gather`, if the settings have one).
ErrorSummary trueErrorNow(const RadiositySolve& solve, const MeshedScene& scene, const TrueError& truth,
                          bool gather = false);

/// A library message with each setting it names (solver.NAME) followed by its flag.
std::string withFlags(const std::string& message);

/// Prints the loader's and the mesher's warnings on stderr.
void printWarnings(const std::vector<std::string>& warnings);

}  // namespace rad::cli
