// radview: draws a radiosity result (the PLY of `radiosity solve`), or a scene lit by OpenGL's
// fixed-function model (--mode local), offscreen into a PNG with OSMesa's OpenGL or the raster
// core. Exit 0 on success, 1 on bad input or failure, 2 on a usage error.
#include <chrono>
#include <cstdio>
#include <iostream>
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
      "light_model, materials, fog) through OSMesa only."};
  std::string input, output, hdr, shade = "smooth", backend = "osmesa", camera, mode = "radiosity",
      scenePath;
  RenderOptions o;
  double exposure = 0;
  app.add_option("result", input, "Result PLY written by `radiosity solve` (--mode radiosity)");
  app.add_option("--mode", mode,
                 "radiosity: draw RESULT.ply (default); local: draw --scene with OpenGL lighting "
                 "(OSMesa only: not with --backend software, --exposure or --hdr)")
      ->check(CLI::IsMember({"radiosity", "local"}));
  app.add_option("--scene", scenePath, "Scene JSON with `lights`, for --mode local");
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
  app.add_flag("--wireframe", o.wireframe, "Overlay the element edges in a dark colour (osmesa only)");
  app.add_option("--camera", camera,
                 "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F as gluLookAt/gluPerspective, fov vertical "
                 "in degrees; any subset overrides the file's `camera` comment");
  app.add_option("--ssaa", o.ssaa, "Supersampling: render K times larger, box filter in linear light")
      ->check(CLI::Range(1, 16));
  app.add_option("--hdr", hdr, "Also write the linear radiance B/pi as Radiance HDR (.hdr)");
  try {
    app.parse(argc, argv);
    if (mode == "radiosity") {
      if (input.empty()) throw CLI::ValidationError("result", "RESULT.ply is required (--mode radiosity)");
      if (!scenePath.empty())
        throw CLI::ValidationError("--scene", "belongs to --mode local; --mode radiosity takes RESULT.ply");
    } else {
      if (scenePath.empty()) throw CLI::ValidationError("--scene", "SCENE.json is required with --mode local");
      if (!input.empty())
        throw CLI::ValidationError("result", "--mode local takes --scene SCENE.json, not a result PLY");
      if (backend == "software")
        throw CLI::ValidationError("--backend", "--mode local is OpenGL-only: use --backend osmesa");
      if (*exposureOption) throw CLI::ValidationError("--exposure", "is radiosity-only, not for --mode local");
      if (!hdr.empty()) throw CLI::ValidationError("--hdr", "is radiosity-only, not for --mode local");
    }
    if (o.wireframe && backend == "software")
      throw CLI::ValidationError("--wireframe", "is OpenGL-only: use it with --backend osmesa");
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
  try {
    rad::checkOutputPath(output);
    if (!hdr.empty()) rad::checkOutputPath(hdr);
    Image image;
    std::chrono::steady_clock::time_point start;
    if (mode == "local") {
      LocalScene local = loadLocalScene(scenePath);
      for (const auto& w : local.scene.warnings) std::cerr << "radview: warning: " << w << "\n";
      if (!camera.empty()) o.camera = parseCamera(camera, effectiveCamera(local, RenderOptions{}));
      start = std::chrono::steady_clock::now();
      image = renderLocal(local, o);
    } else {
      ResultMesh mesh = loadResult(input);
      if (!camera.empty()) o.camera = parseCamera(camera, effectiveCamera(mesh, RenderOptions{}));
      start = std::chrono::steady_clock::now();
      image = render(mesh, o);
    }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writePng(output, image);
    if (!hdr.empty()) writeHdr(hdr, image);
    char line[256];
    std::snprintf(line, sizeof line, "radview: rendered %dx%d (%s%s, %s shading, ssaa %d) in %.3f s; wrote ",
                  o.width, o.height, mode == "local" ? "local lighting, " : "", backend.c_str(), shade.c_str(), o.ssaa, seconds);
    std::cerr << line << output << (hdr.empty() ? "" : " and " + hdr) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "radview: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
