// radview: draws a radiosity result (the PLY of `radiosity solve`), or a scene lit by OpenGL's
// fixed-function model (--mode local), offscreen into a PNG with OSMesa's OpenGL or the raster
// core. Exit 0 on success, 1 on bad input or failure, 2 on a usage error.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <new>
#include <string>

#include <CLI/CLI.hpp>

#include "display/viewer.h"
#include "mesh/error.h"
#include "mesh/output_file.h"

int main(int argc, char** argv) {
  using namespace rad::viewer;
  CLI::App app{
      "radview: draw a radiosity result (the PLY of `radiosity solve`) offscreen into a PNG.\n"
      "Display colour: sRGB(clamp(K*B)), B the vertex radiosity (smooth) or the element's own "
      "(flat).\n"
      "--mode local draws --scene SCENE.json lit by OpenGL's fixed-function model (its lights, "
      "light_model, materials, fog) through OSMesa only.\n"
      "--mode hybrid draws RESULT.ply's radiosity as the diffuse part plus the specular highlights "
      "of --scene SCENE.json's lights and materials (OSMesa only)."};
  std::string input, output, hdr, shade = "smooth", backend = "osmesa", camera, mode = "radiosity",
      scenePath, cull = "none";
  RenderOptions o;
  double exposure = 0;
  app.add_option("result", input, "Result PLY written by `radiosity solve` (--mode radiosity)");
  app.add_option("--mode", mode,
                 "radiosity: draw RESULT.ply (default); local: draw --scene with OpenGL lighting "
                 "(OSMesa only: not with --backend software, --exposure or --hdr); hybrid: "
                 "RESULT.ply's radiosity plus --scene's specular highlights (OSMesa only, no --hdr)")
      ->check(CLI::IsMember({"radiosity", "local", "hybrid"}));
  app.add_option("--scene", scenePath,
                 "Scene JSON with `lights`, for --mode local, --mode hybrid and --ladder (for the last "
                 "two, the scene RESULT.ply was solved from)");
  app.add_option("-o,--output", output, "PNG image to write")->required();
  app.add_option("--width", o.width, "Image width in pixels (default 512)")->check(CLI::Range(1, 16384));
  app.add_option("--height", o.height, "Image height in pixels (default 512)")->check(CLI::Range(1, 16384));
  app.add_option("--shade", shade,
                 "smooth: Gouraud on vertex radiosity (default); flat: each element's own value "
                 "(--mode local: vertex normals, or face normals with GL_FLAT)")
      ->check(CLI::IsMember({"smooth", "flat"}));
  app.add_option("--backend", backend,
                 "osmesa: OpenGL through OSMesa (default); software: the raster core, same picture "
                 "(radiosity mode only)")
      ->check(CLI::IsMember({"osmesa", "software"}));
  auto* exposureOption =
      app.add_option("--exposure", exposure, "Exposure K (default: the file's `exposure` comment)")
          ->check(CLI::PositiveNumber);
  auto* cullOption =
      app.add_option("--cull", cull,
                     "none: draw every face (default); back: remove back faces, clockwise on "
                     "screen (GL_CULL_FACE with GL_BACK, CCW front faces; both backends; radiosity "
                     "mode only)")
          ->check(CLI::IsMember({"none", "back"}));
  app.add_flag("--wireframe", o.wireframe, "Overlay the element edges in a dark colour (both backends)");
  app.add_option("--camera", camera,
                 "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F as gluLookAt/gluPerspective, fov vertical "
                 "in degrees; any subset overrides the file's `camera` comment");
  app.add_option("--ssaa", o.ssaa, "Supersampling: render K times larger, box filter in linear light")
      ->check(CLI::Range(1, 16));
  bool ladder = false;
  app.add_flag("--ladder", ladder,
               "Write the realism ladder of RESULT.ply and --scene SCENE.json as one 4x2 grid of "
               "WxH tiles: wireframe, hidden surfaces removed, flat local, smooth local, smooth "
               "local with specular, radiosity flat, radiosity Gouraud (OSMesa; not with "
               "--wireframe or --hdr)");
  app.add_option("--hdr", hdr, "Also write the linear radiance B/pi as Radiance HDR (.hdr)");
  try {
    app.parse(argc, argv);
    if (*cullOption && (ladder || mode != "radiosity"))
      throw CLI::ValidationError("--cull", "is radiosity-only, not for --mode local, --mode hybrid or --ladder");
    if (ladder) {
      if (mode != "radiosity") throw CLI::ValidationError("--ladder", "draws every mode itself: no --mode");
      if (input.empty()) throw CLI::ValidationError("result", "RESULT.ply is required with --ladder");
      if (scenePath.empty()) throw CLI::ValidationError("--scene", "SCENE.json is required with --ladder");
      if (backend == "software")
        throw CLI::ValidationError("--backend", "--ladder needs OpenGL: use --backend osmesa");
      if (o.wireframe) throw CLI::ValidationError("--wireframe", "not with --ladder (it has its own tile)");
      if (!hdr.empty()) throw CLI::ValidationError("--hdr", "not with --ladder");
    } else if (mode == "radiosity") {
      if (input.empty()) throw CLI::ValidationError("result", "RESULT.ply is required (--mode radiosity)");
      if (!scenePath.empty())
        throw CLI::ValidationError("--scene", "belongs to --mode local, --mode hybrid or --ladder; --mode radiosity takes RESULT.ply");
    } else if (mode == "hybrid") {
      if (input.empty()) throw CLI::ValidationError("result", "RESULT.ply is required (--mode hybrid)");
      if (scenePath.empty()) throw CLI::ValidationError("--scene", "SCENE.json is required with --mode hybrid");
      if (backend == "software")
        throw CLI::ValidationError("--backend", "--mode hybrid is OpenGL-only: use --backend osmesa");
      if (!hdr.empty()) throw CLI::ValidationError("--hdr", "is radiosity-only, not for --mode hybrid");
    } else {
      if (scenePath.empty()) throw CLI::ValidationError("--scene", "SCENE.json is required with --mode local");
      if (!input.empty())
        throw CLI::ValidationError("result", "--mode local takes --scene SCENE.json, not a result PLY");
      if (backend == "software")
        throw CLI::ValidationError("--backend", "--mode local is OpenGL-only: use --backend osmesa");
      if (*exposureOption) throw CLI::ValidationError("--exposure", "is radiosity-only, not for --mode local");
      if (!hdr.empty()) throw CLI::ValidationError("--hdr", "is radiosity-only, not for --mode local");
    }
    if (int64_t(o.width) * o.ssaa > 16384 || int64_t(o.height) * o.ssaa > 16384)
      throw CLI::ValidationError("--ssaa", "width and height times --ssaa must be at most 16384");
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);  // prints help, or the usage error
    return code == 0 ? 0 : 2;
  }
  o.shade = shade == "flat" ? Shading::Flat : Shading::Smooth;
  o.backend = backend == "software" ? Backend::Software : Backend::OsMesa;
  if (*exposureOption) o.exposure = exposure;
  o.radiance = !hdr.empty();
  o.cullBack = cull == "back";
  try {
    rad::checkOutputPath(output);
    if (!hdr.empty()) rad::checkOutputPath(hdr);
    Image image;
    std::chrono::steady_clock::time_point start;
    if (ladder) {
      rad::ResultFile mesh = rad::readResultFile(input);
      rad::Scene scene = rad::loadScene(scenePath);
      for (const auto& w : scene.warnings) std::cerr << "radview: warning: " << w << "\n";
      if (!camera.empty()) o.camera = parseCamera(camera, effectiveCamera(mesh, RenderOptions{}));
      start = std::chrono::steady_clock::now();
      image = renderLadder(mesh, scene, o);
    } else if (mode == "local") {
      LocalScene local = loadLocalScene(scenePath);
      for (const auto& w : local.scene.warnings) std::cerr << "radview: warning: " << w << "\n";
      if (!camera.empty()) o.camera = parseCamera(camera, effectiveCamera(local, RenderOptions{}));
      start = std::chrono::steady_clock::now();
      image = renderLocal(local, o);
    } else if (mode == "hybrid") {
      rad::ResultFile mesh = rad::readResultFile(input);
      rad::Scene scene = rad::loadScene(scenePath);
      for (const auto& w : scene.warnings) std::cerr << "radview: warning: " << w << "\n";
      if (!camera.empty()) o.camera = parseCamera(camera, effectiveCamera(mesh, RenderOptions{}));
      start = std::chrono::steady_clock::now();
      image = renderHybrid(mesh, scene, o);
    } else {
      rad::ResultFile mesh = rad::readResultFile(input);
      if (!camera.empty()) o.camera = parseCamera(camera, effectiveCamera(mesh, RenderOptions{}));
      start = std::chrono::steady_clock::now();
      image = render(mesh, o);
    }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writePng(output, image);
    if (!hdr.empty()) writeHdr(hdr, image);
    char line[256];
    std::snprintf(line, sizeof line, "radview: rendered %dx%d (%s%s%s, %s shading, ssaa %d) in %.3f s; wrote ",
                  image.width, image.height, ladder ? "ladder, " : "", mode == "local" ? "local lighting, " : mode == "hybrid" ? "hybrid, " : "", backend.c_str(), shade.c_str(), o.ssaa, seconds);
    std::cerr << line << output << (hdr.empty() ? "" : " and " + hdr) << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "radview: error: out of memory: the picture or the mesh needs more than this machine "
                 "has (lower --width, --height or --ssaa)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "radview: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
