// radview: draws a radiosity result (the PLY of `radiosity solve`), or a scene lit by OpenGL's
// fixed-function model (--mode local), offscreen into a PNG with OSMesa's OpenGL or the raster
// core. Exit 0 on success, 1 on bad input or failure, 2 on a usage error.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <new>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "display/viewer/viewer.h"
#include "mesh/base/error.h"
#include "mesh/base/output_file.h"
#include "mesh/scene/readers/scene_loader.h"

namespace {

using namespace rad::viewer;

/// The command line as given.
struct Args {
  std::string input, output, hdr, shade = "smooth", backend = "osmesa", camera, mode = "radiosity",
      scenePath, cull = "none";
  double exposure = 0;
  bool ladder = false;
  RenderOptions o;
  CLI::Option* exposureOption = nullptr;
  CLI::Option* cullOption = nullptr;
};

/// --mode: what is drawn.
void addModeOption(CLI::App& app, Args& a) {
  app.add_option("--mode", a.mode,
                 "radiosity: draw RESULT.ply (default); local: draw --scene with OpenGL lighting "
                 "(OSMesa only: not with --backend software, --exposure or --hdr); hybrid: "
                 "RESULT.ply's radiosity plus --scene's specular highlights (OSMesa only, no --hdr)")
      ->check(CLI::IsMember({"radiosity", "local", "hybrid"}));
}

/// The options that say what is drawn and where it goes: the result, the mode, the scene, the
/// picture.
void addInputOptions(CLI::App& app, Args& a) {
  app.add_option("result", a.input, "Result PLY written by `radiosity solve` (--mode radiosity)");
  addModeOption(app, a);
  app.add_option("--scene", a.scenePath,
                 "Scene JSON with `lights`, for --mode local, --mode hybrid and --ladder (for the last "
                 "two, the scene RESULT.ply was solved from)");
  app.add_option("-o,--output", a.output, "PNG image to write")->required();
}

/// The picture's size in pixels.
void addSizeOptions(CLI::App& app, Args& a) {
  app.add_option("--width", a.o.width, "Image width in pixels (default 512)")->check(CLI::Range(1, 16384));
  app.add_option("--height", a.o.height, "Image height in pixels (default 512)")->check(CLI::Range(1, 16384));
}

/// --shade: smooth or flat.
void addShadeOption(CLI::App& app, Args& a) {
  app.add_option("--shade", a.shade,
                 "smooth: Gouraud on vertex radiosity (default); flat: each element's own value "
                 "(--mode local: vertex normals, or face normals with GL_FLAT)")
      ->check(CLI::IsMember({"smooth", "flat"}));
}

/// --backend: OSMesa or the raster core.
void addBackendOption(CLI::App& app, Args& a) {
  app.add_option("--backend", a.backend,
                 "osmesa: OpenGL through OSMesa (default); software: the raster core, same picture "
                 "(radiosity mode only)")
      ->check(CLI::IsMember({"osmesa", "software"}));
}

/// How colours are made: shading, backend, exposure.
void addShadingOptions(CLI::App& app, Args& a) {
  addShadeOption(app, a);
  addBackendOption(app, a);
  a.exposureOption = app.add_option("--exposure", a.exposure, "Exposure K (default: the file's `exposure` comment)")
                         ->check(CLI::PositiveNumber);
}

/// --cull: none or back faces.
void addCullOption(CLI::App& app, Args& a) {
  a.cullOption = app.add_option("--cull", a.cull,
                                "none: draw every face (default); back: remove back faces, clockwise on "
                                "screen (GL_CULL_FACE with GL_BACK, CCW front faces; both backends; radiosity "
                                "mode only)")
                     ->check(CLI::IsMember({"none", "back"}));
}

/// What is seen and how finely: culling, the element edges, the camera, supersampling.
void addViewOptions(CLI::App& app, Args& a) {
  addCullOption(app, a);
  app.add_flag("--wireframe", a.o.wireframe, "Overlay the element edges in a dark colour (both backends)");
  app.add_option("--camera", a.camera,
                 "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F as gluLookAt/gluPerspective, fov vertical "
                 "in degrees; any subset overrides the file's `camera` comment");
  app.add_option("--ssaa", a.o.ssaa, "Supersampling: render K times larger, box filter in linear light")
      ->check(CLI::Range(1, 16));
}

/// The other pictures: the realism ladder instead, the radiance beside.
void addOtherPictureOptions(CLI::App& app, Args& a) {
  app.add_flag("--ladder", a.ladder,
               "Write the realism ladder of RESULT.ply and --scene SCENE.json as one 4x2 grid of "
               "WxH tiles: wireframe, hidden surfaces removed, flat local, smooth local, smooth "
               "local with specular, radiosity flat, radiosity Gouraud (OSMesa; not with "
               "--wireframe or --hdr)");
  app.add_option("--hdr", a.hdr, "Also write the linear radiance B/pi as Radiance HDR (.hdr)");
}

/// Every option, in the order --help lists them.
void addOptions(CLI::App& app, Args& a) {
  addInputOptions(app, a);
  addSizeOptions(app, a);
  addShadingOptions(app, a);
  addViewOptions(app, a);
  addOtherPictureOptions(app, a);
}

/// Usage checks of what --ladder needs: no --mode, a result and a scene.
void checkLadderInputs(const Args& a) {
  if (a.mode != "radiosity") throw CLI::ValidationError("--ladder", "draws every mode itself: no --mode");
  if (a.input.empty()) throw CLI::ValidationError("result", "RESULT.ply is required with --ladder");
  if (a.scenePath.empty()) throw CLI::ValidationError("--scene", "SCENE.json is required with --ladder");
}

/// Usage checks of --ladder.
void checkLadderArgs(const Args& a) {
  checkLadderInputs(a);
  if (a.backend == "software")
    throw CLI::ValidationError("--backend", "--ladder needs OpenGL: use --backend osmesa");
  if (a.o.wireframe) throw CLI::ValidationError("--wireframe", "not with --ladder (it has its own tile)");
  if (!a.hdr.empty()) throw CLI::ValidationError("--hdr", "not with --ladder");
}

/// Usage checks of --mode radiosity.
void checkRadiosityArgs(const Args& a) {
  if (a.input.empty()) throw CLI::ValidationError("result", "RESULT.ply is required (--mode radiosity)");
  if (!a.scenePath.empty())
    throw CLI::ValidationError("--scene", "belongs to --mode local, --mode hybrid or --ladder; --mode radiosity takes RESULT.ply");
}

/// Usage check of an OpenGL-only `mode`: not --backend software.
void checkOpenGlBackend(const Args& a, const std::string& mode) {
  if (a.backend == "software")
    throw CLI::ValidationError("--backend", mode + " is OpenGL-only: use --backend osmesa");
}

/// Usage check of a `mode` without radiance: no --hdr.
void checkNoHdr(const Args& a, const std::string& mode) {
  if (!a.hdr.empty()) throw CLI::ValidationError("--hdr", "is radiosity-only, not for " + mode);
}

/// Usage checks of --mode hybrid.
void checkHybridArgs(const Args& a) {
  if (a.input.empty()) throw CLI::ValidationError("result", "RESULT.ply is required (--mode hybrid)");
  if (a.scenePath.empty()) throw CLI::ValidationError("--scene", "SCENE.json is required with --mode hybrid");
  checkOpenGlBackend(a, "--mode hybrid");
  checkNoHdr(a, "--mode hybrid");
}

/// Usage checks of --mode local.
void checkLocalArgs(const Args& a) {
  if (a.scenePath.empty()) throw CLI::ValidationError("--scene", "SCENE.json is required with --mode local");
  if (!a.input.empty())
    throw CLI::ValidationError("result", "--mode local takes --scene SCENE.json, not a result PLY");
  checkOpenGlBackend(a, "--mode local");
  if (*a.exposureOption) throw CLI::ValidationError("--exposure", "is radiosity-only, not for --mode local");
  checkNoHdr(a, "--mode local");
}

/// The supersampled picture must stay within the largest size.
void checkSupersampledSize(const Args& a) {
  if (int64_t(a.o.width) * a.o.ssaa > 16384 || int64_t(a.o.height) * a.o.ssaa > 16384)
    throw CLI::ValidationError("--ssaa", "width and height times --ssaa must be at most 16384");
}

/// --cull is for radiosity mode alone.
void checkCullArgs(const Args& a) {
  if (*a.cullOption && (a.ladder || a.mode != "radiosity"))
    throw CLI::ValidationError("--cull", "is radiosity-only, not for --mode local, --mode hybrid or --ladder");
}

/// The usage checks of the chosen mode (or the ladder).
void checkModeArgs(const Args& a) {
  if (a.ladder) checkLadderArgs(a);
  else if (a.mode == "radiosity") checkRadiosityArgs(a);
  else if (a.mode == "hybrid") checkHybridArgs(a);
  else checkLocalArgs(a);
}

/// The usage checks after parsing: which options go with which mode. Throws CLI::ValidationError.
void checkArgs(const Args& a) {
  checkCullArgs(a);
  checkModeArgs(a);
  checkSupersampledSize(a);
}

/// The render options the arguments give.
RenderOptions renderOptions(const Args& a) {
  RenderOptions o = a.o;
  o.shade = a.shade == "flat" ? Shading::Flat : Shading::Smooth;
  o.backend = a.backend == "software" ? Backend::Software : Backend::OsMesa;
  if (*a.exposureOption) o.exposure = a.exposure;
  o.radiance = !a.hdr.empty();
  o.cullBack = a.cull == "back";
  return o;
}

/// Prints the repairs the scene loader made.
void printWarnings(const rad::Scene& scene) {
  for (const auto& w : scene.warnings) std::cerr << "radview: warning: " << w << "\n";
}

/// A render and the seconds it took (loading not counted).
struct Rendered {
  Image image;
  double seconds = 0;
};

/// Times `draw` (a callable returning the Image).
template <class Draw>
Rendered timed(Draw draw) {
  const auto start = std::chrono::steady_clock::now();
  Rendered r;
  r.image = draw();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

/// Applies --camera, when given, over the view `source` (the result or the local scene) gives.
template <class Source>
void applyCameraArg(const Args& a, const Source& source, RenderOptions& o) {
  if (!a.camera.empty()) o.camera = parseCamera(a.camera, effectiveCamera(source, RenderOptions{}));
}

/// --mode local: loads the scene, applies --camera over its view, and renders it lit.
Rendered renderLocalMode(const Args& a, RenderOptions o) {
  const LocalScene local = loadLocalScene(a.scenePath);
  printWarnings(local.scene);
  applyCameraArg(a, local, o);
  return timed([&] { return renderLocal(local, o); });
}

/// The scene the ladder and hybrid mode light the result with; empty for --mode radiosity.
rad::Scene sceneBesideResult(const Args& a) {
  rad::Scene scene;
  if (!a.ladder && a.mode != "hybrid") return scene;
  scene = rad::loadScene(a.scenePath);
  printWarnings(scene);
  return scene;
}

/// Draws and times the chosen picture of the result: the ladder, hybrid or radiosity.
Rendered renderResultPicture(const Args& a, const rad::ResultFile& mesh, const rad::Scene& scene,
                             const RenderOptions& o) {
  if (a.ladder) return timed([&] { return renderLadder(mesh, scene, o); });
  if (a.mode == "hybrid") return timed([&] { return renderHybrid(mesh, scene, o); });
  return timed([&] { return render(mesh, o); });
}

/// The modes that draw a result (radiosity, hybrid, the ladder): loads the result and the
/// scene beside it, applies --camera over the result's view, and renders.
Rendered renderResultMode(const Args& a, RenderOptions o) {
  const rad::ResultFile mesh = rad::readResultFile(a.input);
  const rad::Scene scene = sceneBesideResult(a);
  applyCameraArg(a, mesh, o);
  return renderResultPicture(a, mesh, scene, o);
}

/// Loads the inputs of the chosen mode, applies --camera over the view they give, and renders.
Rendered renderRequested(const Args& a, const RenderOptions& o) {
  if (a.mode == "local") return renderLocalMode(a, o);
  return renderResultMode(a, o);
}

/// The report's opening: what was drawn, how, and in how long.
std::string renderedLine(const Args& a, const RenderOptions& o, const Rendered& r) {
  const char* what = a.mode == "local" ? "local lighting, " : a.mode == "hybrid" ? "hybrid, " : "";
  char line[256];
  std::snprintf(line, sizeof line, "radview: rendered %dx%d (%s%s%s, %s shading, ssaa %d) in %.3f s; wrote ",
                r.image.width, r.image.height, a.ladder ? "ladder, " : "", what, a.backend.c_str(),
                a.shade.c_str(), o.ssaa, r.seconds);
  return line;
}

/// Writes the pictures and says what was drawn, how, in how long, and where it went.
void writeAndReport(const Args& a, const RenderOptions& o, const Rendered& r) {
  writePng(a.output, r.image);
  if (!a.hdr.empty()) writeHdr(a.hdr, r.image);
  std::cerr << renderedLine(a, o, r) << a.output << (a.hdr.empty() ? "" : " and " + a.hdr) << "\n";
}

/// Checks the output paths, renders and writes; errors are thrown.
void run(const Args& a) {
  const RenderOptions o = renderOptions(a);
  rad::checkOutputPath(a.output);
  if (!a.hdr.empty()) rad::checkOutputPath(a.hdr);
  writeAndReport(a, o, renderRequested(a, o));
}

/// Prints "radview: error: <what>"; the exit code of an error, 1.
int reportError(const char* what) {
  std::cerr << "radview: error: " << what << "\n";
  return 1;
}

/// Runs, printing any error as "radview: error: ..."; the exit code.
int runReportingErrors(const Args& a) {
  try {
    run(a);
  } catch (const std::bad_alloc&) {
    return reportError("out of memory: the picture or the mesh needs more than this machine has (lower "
                       "--width, --height or --ssaa)");
  } catch (const std::exception& e) {
    return reportError(e.what());
  }
  return 0;
}

/// Parses and checks the command line; the exit code when it stops there (0 after --help, 2
/// on a usage error), else none.
std::optional<int> parseCommandLine(CLI::App& app, Args& args, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    checkArgs(args);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, or the usage error
    return code == 0 ? 0 : 2;
  }
  return std::nullopt;
}

const char* const kDescription =
    "radview: draw a radiosity result (the PLY of `radiosity solve`) offscreen into a PNG.\n"
    "Display colour: sRGB(clamp(K*B)), B the vertex radiosity (smooth) or the element's own "
    "(flat).\n"
    "--mode local draws --scene SCENE.json lit by OpenGL's fixed-function model (its lights, "
    "light_model, materials, fog) through OSMesa only.\n"
    "--mode hybrid draws RESULT.ply's radiosity as the diffuse part plus the specular highlights "
    "of --scene SCENE.json's lights and materials (OSMesa only).";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription};
  Args args;
  addOptions(app, args);
  if (const std::optional<int> code = parseCommandLine(app, args, argc, argv)) return *code;
  return runReportingErrors(args);
}
