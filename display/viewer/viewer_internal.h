#pragma once
// What the viewer's files share and nobody else needs: supersampling, checks of the render
// options, and the per-surface batches of the lit models. Not a public header.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "display/raster/raster.h"
#include "display/viewer/viewer.h"
#include "mesh/results/result_file.h"
#include "mesh/scene/scene.h"

namespace rad::viewer::internal {

/// A [0, 1] value as a display byte, rounded.
uint8_t toByte(float v);

/// The raster target's colours as bytes (RGB, the target's rows: bottom row first).
std::vector<uint8_t> targetBytes(const raster::Target& target);

/// The raster target's colours as RGB values convert(channel) (the target's rows: bottom row first).
template <class T, class Convert>
std::vector<T> targetRgb(const raster::Target& target, Convert convert) {
  std::vector<T> rgb(target.color.size() * 3);
  for (size_t p = 0; p < target.color.size(); ++p)
    for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = convert(target.color[p][c]);
  return rgb;
}

/// A width × height picture of `channels` values per pixel, stored bottom row first, in reading
/// order: top row first.
template <class T>
std::vector<T> topRowFirst(const std::vector<T>& bottomUp, int width, int height, int channels) {
  const size_t row = size_t(width) * channels;
  std::vector<T> out(row * height);
  for (int y = 0; y < height; ++y)
    std::copy_n(&bottomUp[size_t(height - 1 - y) * row], row, &out[size_t(y) * row]);
  return out;
}

/// Box-filters a (width·k) × (height·k) picture of bytes (sRGB, bottom row first) down to
/// width × height, top row first, averaging in linear light.
std::vector<uint8_t> downsampleBytes(const std::vector<uint8_t>& big, int width, int height, int k);

/// The same for linear floats: a plain average.
std::vector<float> downsampleFloats(const std::vector<float>& big, int width, int height, int k);

/// The picture of a render at options.width × options.height from its supersampled bytes
/// (bottom row first, options.ssaa times larger per axis).
Image imageOf(const std::vector<uint8_t>& big, const RenderOptions& options);

/// The camera of a render at its drawn size: options.width × options.height times ssaa.
struct FrameView {
  int width = 0, height = 0;
  glm::mat4 projection{1.0f}, view{1.0f}, mvp{1.0f};
};

/// The view of `mesh` through camera `c` at the drawn size of `options` (viewProjection).
FrameView frameView(const ResultFile& mesh, const Camera& c, const RenderOptions& options);

/// The points in clip space: raster::transform by `mvp`.
std::vector<glm::vec4> clipCoordinates(const glm::mat4& mvp, const std::vector<glm::vec3>& points);

/// The picture, at the size of `options`, of a lit model's draw list in view `v`, drawn through
/// OSMesa by `renderLit` (detail::renderOsMesaLocal or detail::renderOsMesaHybrid).
template <class List, class RenderLit>
Image litPicture(const List& list, const Scene& scene, const FrameView& v, const RenderOptions& options,
                 RenderLit renderLit) {
  std::vector<uint8_t> rgb;
  renderLit(list, scene, v.projection, v.view, v.width, v.height, options.shade, options.wireframe, rgb);
  return imageOf(rgb, options);
}

/// Whether a render draws the file's own display colours: Gouraud at the file's exposure.
bool showsStoredColours(const ResultFile& mesh, const RenderOptions& options);

/// Checks the image size: width and height times ssaa in 1..raster::kMaxSize. Throws InputError.
void checkSize(const RenderOptions& options);

/// Checks that every face has a surface index of `scene`; `where` names the mode. Throws
/// InputError.
void checkFaceSurfaces(const ResultFile& mesh, const Scene& scene, const std::string& where);

/// The batch of a material that carries only its specular colour and shininess.
detail::LocalBatch specularBatch(const Material& m);

/// The largest component of the material's emission (0 for a material that does not emit).
double peakEmission(const Material& m);

/// The items 0..count-1 grouped by their scene surface (surfaceOf(item)), in item order.
template <class SurfaceOf>
std::vector<std::vector<size_t>> groupBySurface(size_t surfaceCount, size_t count, SurfaceOf surfaceOf) {
  std::vector<std::vector<size_t>> groups(surfaceCount);
  for (size_t i = 0; i < count; ++i) groups.at(size_t(surfaceOf(i))).push_back(i);
  return groups;
}

/// One batch per surface that has items, in surface order: the batch starts as
/// makeBatch(surface's material), then addItem(item) appends each item's vertices to `list`,
/// and the batch covers the vertices appended.
template <class List, class MakeBatch, class AddItem>
void appendBatches(List& list, const Scene& scene, const std::vector<std::vector<size_t>>& groups,
                   MakeBatch makeBatch, AddItem addItem) {
  for (size_t s = 0; s < groups.size(); ++s) {
    if (groups[s].empty()) continue;
    detail::LocalBatch b = makeBatch(scene.materials.at(size_t(scene.surfaces[s].material)));
    b.first = int(list.positions.size());
    for (size_t item : groups[s]) addItem(item);
    b.count = int(list.positions.size()) - b.first;
    list.batches.push_back(b);
  }
}

}  // namespace rad::viewer::internal
