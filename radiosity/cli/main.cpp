// radiosity: solve, inspect and mesh radiosity scenes. Exit 0 on success, 1 on bad input or
// failure, 2 on a usage error.
#include <algorithm>
#include <iostream>
#include <map>
#include <regex>
#include <new>
#include <optional>
#include <vector>

#include "mesh/base/error.h"
#include "mesh/base/progress.h"
#include "radiosity/cli/commands.h"

namespace rad::cli {

void addScene(CLI::App& app, std::string& scene) {
  app.add_option("scene", scene, "Scene file (JSON, version 1)")->required();
}

void addSceneAndOutput(CLI::App& app, std::string& scene, std::string& output, const std::string& outputHelp) {
  addScene(app, scene);
  app.add_option("-o,--output", output, outputHelp)->required();
}

namespace {

/// The check of a hemicube resolution's flag: an even number of pixels.
std::string mustBeEven(const std::string& resolution) {
  return std::stoi(resolution) % 2 ? "must be even" : "";
}

/// An option whose value must be positive (a length).
template <class T>
void addPositive(CLI::App& app, const std::string& name, T& slot, const std::string& help) {
  app.add_option(name, slot, help)->check(CLI::PositiveNumber);
}

/// An option whose value must lie in [lo, hi].
template <class T, class Bound>
void addInRange(CLI::App& app, const std::string& name, T& slot, Bound lo, Bound hi, const std::string& help) {
  app.add_option(name, slot, help)->check(CLI::Range(lo, hi));
}

/// A hemicube resolution's option: an even number of pixels across the top face.
void addResolution(CLI::App& app, const std::string& name, std::optional<int>& slot, const std::string& help) {
  app.add_option(name, slot, help)->check(CLI::Range(2, 8192))->check(mustBeEven);
}

/// Element and patch sizes, contacts and the element cap.
void addSizeFlags(CLI::App& app, SolverBlock& flags) {
  static const std::map<std::string, Quality> qualities{
      {"draft", Quality::Draft}, {"default", Quality::Default}, {"final", Quality::Final}};
  app.add_option_function<std::string>(
         "--quality", [&flags](const std::string& name) { flags.quality = qualities.at(name); },
         "What the solve spends for accuracy: draft (a quick look: elements 1.6x as long, coarser "
         "gather), default, or final (elements 1.6x shorter, every vertex gathers); the flags below "
         "override what it sets (solver.quality; default: default)")
      ->check(CLI::IsMember({"draft", "default", "final"}));
  addPositive(app, "--max-element-edge", flags.maxElementEdge,
              "Longest element edge, scene units (solver.max_element_edge; default: scene diagonal / 25; "
              "times 1.6 for a draft, over 1.6 final, the scene's own too)");
  addPositive(app, "--max-patch-edge", flags.maxPatchEdge,
              "Widest patch (shooter), scene units (solver.max_patch_edge; default: 3 element edges)");
  app.add_option("--cut-contacts", flags.cutContacts,
                 "Cut surfaces along the lines where others touch them and leave out what those "
                 "enclose, true or false (solver.cut_contacts; default true)");
  app.add_option("--fix-facing", flags.fixFacing,
                 "Turn round mesh-file surfaces that light from the emitters meets mostly on their "
                 "backs (walls wound outwards), with a warning naming each, true or false "
                 "(solver.fix_facing; default true)");
  addInRange(app, "--max-elements", flags.maxElements, 1L, 1'000'000'000'000L,
             "Refuse meshes of more elements than this, estimated before meshing; adaptive "
             "refinement stops there (solver.max_elements; default 2000000, ~14 GiB)");
}

/// Adaptive refinement and the direct light at the vertices.
void addRefinementFlags(CLI::App& app, SolverBlock& flags) {
  app.add_option("--adaptive", flags.adaptive,
                 "Refine elements where the direct light changes visibly (penumbrae, contacts), "
                 "true or false (solver.adaptive; default true)");
  addPositive(app, "--min-element-edge", flags.minElementEdge,
              "Adaptive refinement stops at elements this small, scene units; where the direct light "
              "changes 8x the contrast across one (a sharp shadow edge), 4x smaller (solver.min_element_edge; "
              "default: element edge / 8 with the final gather, / 4 without)");
  addInRange(app, "--contrast", flags.contrast, 1e-6, 1.0,
             "Adaptive refinement threshold: difference in display value (sRGB, 0 to 1) "
             "across an element (solver.contrast; default 0.02)");
  app.add_option("--vertex-direct", flags.vertexDirect,
                 "Show direct light computed at the vertices by rays to points on the emitters, "
                 "true or false (solver.vertex_direct; default true)");
  app.add_option("--final-gather", flags.finalGather,
                 "Gather the light shown at every vertex through its own hemicube after the solve, "
                 "true or false (solver.final_gather; default true)");
}

/// The hemicube resolutions and the seed of their rotations.
void addHemicubeFlags(CLI::App& app, SolverBlock& flags) {
  addResolution(app, "--hemicube", flags.hemicubeResolution,
                "Hemicube resolution, pixels across the top face, even (solver.hemicube_resolution; "
                "default 128; 64 as the final gather's start)");
  addResolution(app, "--emitter-hemicube", flags.emitterHemicubeResolution,
                "Hemicube resolution for emitting patches, even "
                "(solver.emitter_hemicube_resolution; default 256; 64 as the final gather's start)");
  addResolution(app, "--gather-hemicube", flags.gatherResolution,
                "Hemicube resolution of the final gather at the vertices, even "
                "(solver.gather_resolution; default 32)");
  addInRange(app, "--gather-accuracy", flags.gatherAccuracy, 0.0, 1.0,
             "Which vertices of the final gather render hemicubes: a vertex within this share of a "
             "gathering vertex's mean distance to what it sees interpolates it; 0: every vertex "
             "(solver.gather_accuracy; default 0.2)");
  app.add_option("--seed", flags.seed, "Seed of the hemicube rotations (solver.seed; default 1)");
}

/// Shooting points and the factor cache.
void addShootingFlags(CLI::App& app, SolverBlock& flags) {
  addInRange(app, "--emitter-samples", flags.emitterSamples, 1, 65536,
             "Shooting points on each emitting patch (solver.emitter_samples; default 64; 4 as the final gather's start)");
  addInRange(app, "--shooter-samples", flags.shooterSamples, 1, 65536,
             "Shooting points on each other patch (or cluster of patches), at least (solver.shooter_samples; default 1)");
  addInRange(app, "--proximity-samples", flags.proximitySamples, 0.0, 65536.0,
             "More shooting points near other surfaces: k·(D/d)² for a patch of diameter D "
             "whose nearest facing element lies d away (solver.proximity_samples; default 0.7)");
  app.add_option("--cluster-shooters", flags.clusterShooters,
                 "Let patches of one plane far from other surfaces shoot together from fewer points, "
                 "true or false (solver.cluster_shooters; default true)");
  app.add_option("--resolution-follows-power", flags.resolutionFollowsPower,
                 "Let a patch that first shoots with less unshot power than the strongest shot draw coarser "
                 "hemicubes, down to half the resolution and no coarser than 64, true or false "
                 "(solver.resolution_follows_power; default true)");
  addInRange(app, "--factor-cache-mb", flags.factorCacheMb, 0.0, 1e9,
             "Memory for reusing a patch's form factors when it shoots again, MiB "
             "(solver.factor_cache_mb; default 256; 0: recompute)");
}

}  // namespace

void addMeshFlags(CLI::App& app, SolverBlock& flags) {
  addSizeFlags(app, flags);
  addRefinementFlags(app, flags);
}

void addSolverFlags(CLI::App& app, SolverBlock& flags) {
  addHemicubeFlags(app, flags);
  addShootingFlags(app, flags);
}

MeshedScene meshWithFlags(Scene scene, const SolverBlock& flags, bool requireEmitter) {
  printWarnings(scene.warnings);
  const Settings settings = resolveSettings(scene, flags);
  // Only a solve needs light; its gather's hemicubes render beside the rays.
  return meshScene(std::move(scene), settings,
                   {requireEmitter, [](const std::string& w) { printWarnings({withFlags(w)}); }, requireEmitter});
}

MeshedScene loadAndMesh(const std::string& path, Scene (*load)(const std::string&), const SolverBlock& flags,
                        bool requireEmitter, StageTimes& stages) {
  auto start = StageTimes::Clock::now();
  Scene scene = load(path);
  start = stages.add("loading", start);
  MeshedScene meshed = meshWithFlags(std::move(scene), flags, requireEmitter);
  const StageTimes& meshing = meshed.mesh.stats.stages;
  stages.add(meshing);
  stages.add("direct light and refinement", std::max(0.0, StageTimes::since(start) - meshing.total()));
  return meshed;
}

ErrorSummary trueErrorNow(const RadiositySolve& solve, const MeshedScene& scene, const TrueError& truth,
                          bool gather) {
  return truth.measure(shownAtVertices(scene, solve.bake(gather)));
}

namespace {

/// The command-line flag of a setting of the scene's solver block: one name in both, dashes
/// for underscores, except the hemicube resolutions.
std::string flagOf(const std::string& setting) {
  if (setting == "hemicube_resolution") return "--hemicube";
  if (setting == "emitter_hemicube_resolution") return "--emitter-hemicube";
  std::string flag = "--" + setting;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

}  // namespace

std::string withFlags(const std::string& message) {
  static const std::regex setting(R"(solver\.([a-z_]+))");
  std::string out;
  auto last = message.cbegin();
  for (std::sregex_iterator it(message.begin(), message.end(), setting), end; it != end; ++it) {
    out.append(last, (*it)[0].second);
    out += " (" + flagOf((*it)[1].str()) + ")";
    last = (*it)[0].second;
  }
  return out.append(last, message.cend());
}

void printWarnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::cerr << "radiosity: warning: " << w << "\n";
}

}  // namespace rad::cli

namespace {

/// A long stage's progress line on stderr, as every command says it.
void sayProgress(const std::string& line) {
  std::cerr << "radiosity: " + line + "\n";  // one write: the gather ahead says its own from its thread
}

/// An error on stderr, as every command says it.
void printError(const std::string& message) {
  std::cerr << "radiosity: error: " << message << "\n";
}

/// Every command of the tool, each added to `app`.
std::vector<rad::cli::Command> addCommands(CLI::App& app) {
  return {rad::cli::addSolveCommand(app),       rad::cli::addInfoCommand(app),
          rad::cli::addMeshCommand(app),        rad::cli::addFormFactorsCommand(app),
          rad::cli::addConvergenceCommand(app), rad::cli::addReferenceCommand(app)};
}

/// What a run that ran out of memory says.
constexpr const char* kOutOfMemory =
    "out of memory: the scene's mesh and factors need more than this machine has (raise "
    "--max-element-edge or lower --max-elements and --factor-cache-mb)";

/// Runs the command the user chose.
void runParsed(const std::vector<rad::cli::Command>& commands) {
  for (const auto& command : commands)
    if (command.app->parsed()) command.run();
}

/// Runs the parsed command; errors are said on stderr with exit status 1.
int runReportingErrors(const std::vector<rad::cli::Command>& commands) {
  try {
    runParsed(commands);
    return 0;
  } catch (const rad::SettingError& e) {
    printError(rad::cli::withFlags(e.what()));
  } catch (const std::bad_alloc&) {
    printError(kOutOfMemory);
  } catch (const std::exception& e) {  // InputError and the rest
    printError(e.what());
  }
  return 1;
}

/// Parses the command line; the exit status when that ends the run (help: 0, a usage
/// error: 2), none when a command is to run.
std::optional<int> parseOrExit(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, or the usage error
    return code == 0 ? 0 : 2;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Progressive radiosity: solve, inspect and mesh scenes of diffuse surfaces"};
  app.require_subcommand(1);
  const std::vector<rad::cli::Command> commands = addCommands(app);
  if (const std::optional<int> code = parseOrExit(app, argc, argv)) return *code;
  const rad::ProgressScope progress(sayProgress);
  return runReportingErrors(commands);
}
