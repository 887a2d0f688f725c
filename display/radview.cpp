// radview: draws a radiosity result (the PLY of `radiosity solve`) offscreen into a PNG, with
// OSMesa's OpenGL or the raster core. Exit 0 on success, 1 on bad input or failure, 2 on a usage
// error.
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
      "(flat)."};
  std::string input, output, hdr, shade = "smooth", backend = "osmesa", camera;
  RenderOptions o;
  double exposure = 0;
  app.add_option("result", input, "Result PLY written by `radiosity solve`")->required();
  app.add_option("-o,--output", output, "PNG image to write")->required();
  app.add_option("--width", o.width, "Image width in pixels (default 512)")->check(CLI::Range(1, 16384));
  app.add_option("--height", o.height, "Image height in pixels (default 512)")->check(CLI::Range(1, 16384));
  app.add_option("--shade", shade,
                 "smooth: Gouraud on vertex radiosity (default); flat: each element's own value")
      ->check(CLI::IsMember({"smooth", "flat"}));
  app.add_option("--backend", backend,
                 "osmesa: OpenGL through OSMesa (default); software: the raster core, same picture")
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
    ResultMesh mesh = loadResult(input);
    if (!camera.empty()) o.camera = parseCamera(camera, effectiveCamera(mesh, RenderOptions{}));
    auto start = std::chrono::steady_clock::now();
    Image image = render(mesh, o);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writePng(output, image);
    if (!hdr.empty()) writeHdr(hdr, image);
    char line[256];
    std::snprintf(line, sizeof line, "radview: rendered %dx%d (%s, %s shading, ssaa %d) in %.3f s; wrote ",
                  o.width, o.height, backend.c_str(), shade.c_str(), o.ssaa, seconds);
    std::cerr << line << output << (hdr.empty() ? "" : " and " + hdr) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "radview: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
